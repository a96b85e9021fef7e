// SPDX-License-Identifier: Apache-2.0
// Image files of a framebuffer's colour buffer: PNG (libpng) and binary PPM.
#pragma once

#include <string>

#include "ref/framebuffer.h"

namespace rastsim {

// Writes the colour buffer as PNG (RGB, alpha dropped since it is always 255) or binary
// PPM, chosen by the extension, at a temporary name renamed over `path` once complete
// (util/atomic_file.h): a failure leaves no file. Throws std::runtime_error naming the
// file on failure.
void write_image(const Framebuffer& fb, const std::string& path);
// Throws write_image's error for a name that is neither .png nor .ppm (checked before a run).
void check_image_path(const std::string& path);
// Reads a PNG or PPM written by write_image back into RGBA8 (for tests and tools).
Framebuffer read_image(const std::string& path);

}  // namespace rastsim
