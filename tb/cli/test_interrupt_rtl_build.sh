#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Ctrl-C on an on-demand RTL build (docs/rtl.md, "Any config through the RTL"): SIGINT
# to the `rastsim` process alone, once the compile stage runs, stops cmake, ninja and
# the compilers, removes the build folder, caches nothing, says so, and exits 130. A
# cache of its own in the test's temporary folder marks the build's processes (their
# command line or working directory lies in it). ctest label rtlbuild: Verilator runs
# first (the configure step), then a few seconds of compiling.
# usage: test_interrupt_rtl_build.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"
export RASTSIM_CACHE="$TMP/cache"

# The processes whose command line or working directory is in the test's cache.
build_processes() {
  local p
  for p in /proc/[0-9]*; do
    { tr '\0' ' ' <"$p/cmdline"; readlink "$p/cwd"; } 2>/dev/null | grep -qF -- "$RASTSIM_CACHE" && echo "${p#/proc/}"
  done
}

set -m  # the build in the background gets SIGINT as from a terminal (not ignored)
"$BIN" cosim --config "$SRC/configs/embedded.toml" --set fifo.tile_depth=3 --rtl-build-only \
  >"$TMP/build.out" 2>"$TMP/build.err" &
pid=$!
for _ in $(seq 3000); do
  grep -q "rtl build: compile" "$TMP/build.err" && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.1
done
if grep -q "rtl build: compile" "$TMP/build.err"; then pass; else
  fail "the build never reached its compile stage: $(tail -3 "$TMP/build.err")"
fi
sleep 3
[ -n "$(build_processes)" ] && pass || fail "no compiler was running when the signal was sent"
kill -INT $pid
wait $pid
rc=$?
[ $rc = 130 ] && pass || fail "interrupted build: exit status $rc, expected 130: $(tail -3 "$TMP/build.err")"
for _ in $(seq 10); do [ -z "$(build_processes)" ] && break; sleep 0.1; done
left="$(build_processes)"
if [ -z "$left" ]; then pass; else
  fail "the build's processes run on: $(for p in $left; do tr '\0' ' ' <"/proc/$p/cmdline" 2>/dev/null | cut -c1-80; echo; done)"
  kill $left 2>/dev/null
fi
entries="$(find "$RASTSIM_CACHE/rtl" -mindepth 1 -maxdepth 1 -type d 2>/dev/null)"
[ -z "$entries" ] && pass || fail "the interrupted build left folders in the cache: $entries"
grep -q "interrupted by SIGINT while building RTL model [0-9a-f]*: its compilers are stopped, nothing was cached" \
  "$TMP/build.err" && pass || fail "the message does not say nothing was cached: $(tail -3 "$TMP/build.err")"

echo "rtlbuild.interrupt: $passes passed, $fails failed"
[ $fails -eq 0 ]
