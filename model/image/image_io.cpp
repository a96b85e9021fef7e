// SPDX-License-Identifier: Apache-2.0
#include "image/image_io.h"

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "util/atomic_file.h"

namespace rastsim {

namespace {
bool ends_with(const std::string& s, const std::string& suf) {
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
}

struct FileCloser {
  void operator()(FILE* f) const { if (f) std::fclose(f); }
};
}  // namespace

namespace {

void write_ppm(const Framebuffer& fb, const std::string& path, const std::string& target) {
  std::ofstream os(path, std::ios::binary);
  if (!os) throw std::runtime_error(target + ": cannot open for writing");
  os << "P6\n" << fb.width << " " << fb.height << "\n255\n";
  // Row by row from the tiles (Framebuffer::read_row): no second full copy.
  std::vector<uint8_t> rgba(size_t(fb.width) * 4), rgb(size_t(fb.width) * 3);
  for (int y = 0; y < fb.height; ++y) {
    fb.read_row(y, rgba.data());
    for (size_t x = 0; x < size_t(fb.width); ++x) std::copy_n(&rgba[x * 4], 3, &rgb[x * 3]);
    os.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
  }
  os.close();
  if (!os) throw std::runtime_error(target + ": write failed");
}

void write_png(const Framebuffer& fb, const std::string& path, const std::string& target) {
  std::unique_ptr<FILE, FileCloser> f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error(target + ": cannot open for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw std::runtime_error(target + ": libpng init failed");
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error(target + ": PNG write failed");
  }
  png_init_io(png, f.get());
  png_set_IHDR(png, info, fb.width, fb.height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  std::vector<uint8_t> row(size_t(fb.width) * 4);  // one row at a time from the tiles
  for (int y = 0; y < fb.height; ++y) {
    fb.read_row(y, row.data());
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f.release()) != 0) throw std::runtime_error(target + ": write failed");
}

}  // namespace

void check_image_path(const std::string& path) {
  if (!ends_with(path, ".ppm") && !ends_with(path, ".png"))
    throw std::runtime_error(path + ": output must end in .png or .ppm");
}

void write_image(const Framebuffer& fb, const std::string& path) {
  check_image_path(path);
  const bool ppm = ends_with(path, ".ppm");
  // At a temporary beside the file, renamed once whole (util/atomic_file.h).
  write_atomically(path, [&](const std::string& tmp) { ppm ? write_ppm(fb, tmp, path) : write_png(fb, tmp, path); });
}

Framebuffer read_image(const std::string& path) {
  if (ends_with(path, ".ppm")) {
    std::ifstream is(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0, maxv = 0;
    is >> magic >> w >> h >> maxv;
    if (!is || magic != "P6" || w <= 0 || h <= 0 || maxv != 255)
      throw std::runtime_error(path + ": not a binary PPM (P6, 8-bit)");
    is.get();
    Framebuffer fb(w, h);
    std::vector<uint8_t> rgb(size_t(w) * 3), rgba(size_t(w) * 4);
    for (int y = 0; y < h && is; ++y) {
      is.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size()));
      for (size_t x = 0; x < size_t(w); ++x) {
        std::copy_n(&rgb[x * 3], 3, &rgba[x * 4]);
        rgba[x * 4 + 3] = 255;
      }
      fb.write_row(y, rgba.data());
    }
    if (!is) throw std::runtime_error(path + ": truncated PPM");
    return fb;
  }
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str()))
    throw std::runtime_error(path + ": " + img.message);
  img.format = PNG_FORMAT_RGBA;
  Framebuffer fb(static_cast<int>(img.width), static_cast<int>(img.height));
  std::vector<uint8_t> rgba(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, rgba.data(), 0, nullptr))
    throw std::runtime_error(path + ": " + img.message);
  for (int y = 0; y < fb.height; ++y) fb.write_row(y, rgba.data() + size_t(y) * size_t(fb.width) * 4);
  return fb;
}

}  // namespace rastsim
