// SPDX-License-Identifier: Apache-2.0
// The version of this rastsim build: `git describe --always --dirty` of the source tree at
// build time, e.g. "57ab2eb" or "57ab2eb-dirty"; "unknown" where the sources are no git
// checkout of their own (an unpacked tarball) or git is missing. Defined in one generated
// file (version.cpp.in, written by version.cmake at every build, touched only when its
// text changes), so a new commit recompiles that one file and relinks, nothing else.
#pragma once

namespace rastsim {

const char* rastsim_version();

}  // namespace rastsim
