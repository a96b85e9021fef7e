# SPDX-License-Identifier: Apache-2.0
# Sourced by scripts/demo and scripts/test: install what is missing, configure, build.
# Safe to run again: installs nothing when every package is present, and the build is
# incremental (Ninja).

set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${RASTSIM_BUILD_DIR:-$ROOT/build}"
JOBS="${RASTSIM_JOBS:-$(nproc)}"

# Debian 12 packages, kept in one place: what scripts/demo needs to build the tool
# (RASTSIM_TOOL_ONLY) and run the demo, then what the rest needs (tests, benchmarks,
# other commands' tools, plots).
RASTSIM_DEMO_PACKAGES=(
  g++ cmake ninja-build pkg-config
  libsystemc-dev verilator
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libpng-dev zlib1g-dev
  libzstd-dev   # zstd-compressed scenes (model/scene/scene_stream.cpp)
  libstb-dev    # stb_image: texture files, PNG, TGA and JPEG (model/scene/texture_file.cpp)
  libdeflate-dev   # its CRC-32 (carry-less multiply) for the framebuffer CRC (model/ref/framebuffer.cpp)
  libgmp-dev   # GMP's mpq_class: exact area coverage (model/aa, docs/exact-coverage.md)
  python3-matplotlib   # scripts/plot_sweep, scripts/side_by_side
)
RASTSIM_PACKAGES=(
  "${RASTSIM_DEMO_PACKAGES[@]}"
  libgtest-dev libbenchmark-dev
  zstd          # the zstd tool: scripts/gen_scenes --compress zst, the CLI test
  time      # GNU time (/usr/bin/time -f %M, peak memory): scripts/bench_scale
  gtkwave   # vcd2fst / fst2vcd for FST video signals (rastsim scanout --signal, monitor), and to view waveforms
  libosmesa6-dev   # OSMesa: Mesa's llvmpipe, headless, the independent renderer of ctest -L mesa (docs/mesa.md)
  yosys     # rastsim area, sweep --area: the RTL synthesised into generic gates (docs/area.md)
  # rastsim sweep --backend slurm, tested for real by scripts/slurm_local (ctest -L slurm) on
  # a one-node cluster. Installed always, as CI runs every label anyway: about 13 MB with
  # their libraries. The script starts daemons of its own (own files and ports) and never
  # uses the system services the packages install (on a systemd host, munge's starts).
  slurm-wlm munge
  # Real meshes (scripts/workloads, ctest -L workloads, scripts/bench_levels): glmark2's
  # models (the Stanford bunny, horse, cat; 6.6 MB download) and assimp to convert the
  # .3ds ones to OBJ (3 MB with libassimp5).
  glmark2-data assimp-utils
  # Real programs' frames (scripts/capture_glmark2, rastsim import-apitrace,
  # scripts/compare_llvmpipe, ctest -L apps, docs/workloads.md): glmark2 run headless under
  # Xvfb on Mesa's llvmpipe, captured and replayed by apitrace.
  apitrace glmark2-x11 xvfb xauth libgl1-mesa-dri
  # libFuzzer targets of the parsers (scripts/fuzz, ctest -L fuzz in build-fuzz/,
  # docs/fuzzing.md): Debian's clang 14 and its compiler-rt (libclang_rt.fuzzer*.a).
  # About 260 MB installed: libllvm14 107 MB, libclang-cpp14 57 MB, libclang1-14 30 MB,
  # libclang-common-14-dev 20 MB, libclang-rt-14-dev 43 MB.
  clang libclang-rt-14-dev
)

# install_missing_packages [PACKAGE...]: those of the given packages (default: all of
# RASTSIM_PACKAGES) that are not installed.
install_missing_packages() {
  local wanted=("$@") missing=()
  [ ${#wanted[@]} -gt 0 ] || wanted=("${RASTSIM_PACKAGES[@]}")
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "setup: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# configure_and_build BUILD_DIR [cmake args...] -- [ninja targets...]: configures a new
# tree with the args, an existing one again only when a -DNAME=VALUE among them differs
# from its cache (scripts/test after scripts/demo: RASTSIM_TOOL_ONLY=OFF); then builds.
configure_and_build() {
  local dir="$1"; shift
  local cmake_args=() targets=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do cmake_args+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  targets=("$@")
  local configure=0 a name
  [ -f "$dir/build.ninja" ] || configure=1
  for a in "${cmake_args[@]}"; do
    [ $configure -eq 0 ] && [[ "$a" == -D*=* ]] || continue
    name="${a#-D}"; name="${name%%=*}"; name="${name%%:*}"
    [ "$(sed -n "s/^${name}:[A-Z]*=//p" "$dir/CMakeCache.txt")" = "${a#*=}" ] || configure=1
  done
  if [ $configure -eq 1 ]; then
    cmake -S "$ROOT" -B "$dir" -G Ninja "${cmake_args[@]}"
  fi
  ninja -C "$dir" -j "$JOBS" "${targets[@]}"
}
