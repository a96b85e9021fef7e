#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Safe defaults and honest errors, as a user meets them with the shipped configs:
# an OBJ mesh draws with a depth test, scan-out decodes the whole framebuffer or says
# why not, `area --top` refuses a module it cannot report before Yosys runs,
# `cosim --rtl-model` names the differing parameter, a sweep's --set names each key and
# value once, and `monitor` neither echoes raw bytes nor reads a device without end.
# usage: test_cli_defaults.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"
PY=/usr/bin/python3
D3D="$SRC/configs/d3d11.toml"
TORUS="$SRC/traces/torus.trace"

# 1. The bunny with the shipped d3d11 config hides its back faces: drawn with the default
#    (scene.obj_depth_func = less) it equals the bunny with its back faces culled (and
#    the same depth test, for the front faces that hide each other); with the config's
#    own depth test (always) it does not (the control: back faces show).
#    (The bunny is closed, and every back-face pixel lies behind a front face here, so
#    hiding by depth and culling by facing give the same pixels; d3d11's front faces are
#    clockwise on screen while the placed OBJ's are counter-clockwise, so its back faces
#    are culled with raster.cull = front.)
BUNNY=/usr/share/glmark2/models/bunny.obj
if [ -r "$BUNNY" ]; then
  crc() { "$BIN" render --config "$D3D" --scene "$BUNNY" --stats "$TMP/b.json" -q "$@" &&
          json_field "$TMP/b.json" framebuffer_crc32; }
  hidden="$(crc)" culled="$(crc --set raster.cull=front)"
  shown="$(crc --set scene.obj_depth_func=config)"
  [ -n "$hidden" ] && [ "$hidden" = "$culled" ] && pass ||
    fail "bunny: default render (crc '$hidden') differs from back faces culled (crc '$culled')"
  [ -n "$shown" ] && [ "$shown" != "$hidden" ] && pass || fail "bunny: depth 'always' draws the same ('$shown')"
  # The same at the timed level: simulate's image is render's.
  "$BIN" simulate --config "$D3D" --scene "$BUNNY" --stats "$TMP/s.json" -q &&
    [ "$(json_field "$TMP/s.json" framebuffer_crc32)" = "$hidden" ] && pass ||
    fail "bunny: simulate's image is not render's with the depth test"
  # A trace keeps the config's depth test (raster.depth_func = always on d3d11).
  a="$("$BIN" render --config "$D3D" --scene "$TORUS" --stats "$TMP/t.json" -q && json_field "$TMP/t.json" framebuffer_crc32)"
  b="$("$BIN" render --config "$D3D" --scene "$TORUS" --set scene.obj_depth_func=config --stats "$TMP/t.json" -q &&
       json_field "$TMP/t.json" framebuffer_crc32)"
  [ -n "$a" ] && [ "$a" = "$b" ] && pass || fail "torus: scene.obj_depth_func changed a trace ($a vs $b)"
else
  echo "note: $BUNNY missing (Debian package glmark2-data): bunny checks skipped"
fi

# 2. Scan-out of the 640x480 configs decodes a 640x480 frame; a framebuffer larger than
#    the video mode is an error naming both sizes, never a silent crop.
png_size() { $PY -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print('%dx%d' % struct.unpack('>II', d[16:24]))" "$1"; }
for cfg in d3d11 embedded; do
  if "$BIN" scanout --config "$SRC/configs/$cfg.toml" --scene "$TORUS" -o "$TMP/so.png" -q; then
    size="$(png_size "$TMP/so.png")"
    [ "$size" = 640x480 ] && pass || fail "scanout $cfg: decoded $size, not 640x480"
  else
    fail "scanout $cfg failed"
  fi
done
expect_error "scanout crop" "640x480.*larger than.*128x128|128x128.*640x480" -- \
  "$BIN" scanout --config "$D3D" --set display.timing=panel --scene "$TORUS" -o "$TMP/crop.png" -q
[ ! -e "$TMP/crop.png" ] && pass || fail "scanout crop: wrote an image"

# 3. area --top refuses a module instantiated with several parameter sets before Yosys
#    runs (a stand-in Yosys records any call), naming the modules it can report; a
#    reportable stage passes the check and reaches Yosys.
cat >"$TMP/yosys" <<EOF
#!/bin/sh
touch "$TMP/yosys_ran"; exit 1
EOF
chmod +x "$TMP/yosys"
for top in rast_hold rast_fifo; do
  RASTSIM_YOSYS="$TMP/yosys" RASTSIM_CACHE="$TMP/cache" expect_error "area --top $top" \
    "--top $top: .*several parameter sets.*rast_tri_setup" -- \
    "$BIN" area --config "$SRC/configs/embedded.toml" --top "$top" -q
done
[ ! -e "$TMP/yosys_ran" ] && pass || fail "area --top rast_hold ran Yosys before refusing"
RASTSIM_YOSYS="$TMP/yosys" RASTSIM_CACHE="$TMP/cache" "$BIN" area --config "$SRC/configs/embedded.toml" \
  --top rast_tri_setup -q >/dev/null 2>&1
[ -e "$TMP/yosys_ran" ] && pass || fail "area --top rast_tri_setup did not reach Yosys"
expect_error "area --top unknown" "--top rast_nothing: not an RTL module; --top takes rast_top, rast_engine2d" -- \
  "$BIN" area --config "$SRC/configs/embedded.toml" --top rast_nothing -q

# 4. cosim --rtl-model with a model built for other parameters names the first differing
#    parameter, its config key and both values (embedded: 4 sub-pixel bits; d3d11's
#    model: 8).
expect_error "cosim --rtl-model" "--rtl-model d3d11: .*CoordInt \(I of raster.coord_format.*\) is 10, the RTL was built with 15" -- \
  "$BIN" cosim --config "$SRC/configs/embedded.toml" --rtl-model d3d11 --scene "$TORUS"

# 5. A sweep's --set gives each key once and each value once, checked before any run.
for sets in "raster.tile_size=8,8" "raster.tile_size=8 raster.tile_size=16,32" \
            "raster.tile_size=16,32 raster.tile_size=8" "raster.tile_size=8 raster.tile_size=16"; do
  args=()
  for s in $sets; do args+=(--set "$s"); done
  expect_error "sweep --set $sets" "raster.tile_size.*(twice|already set by --set raster.tile_size=)" -- \
    "$BIN" sweep --scene "$TORUS" "${args[@]}" --out "$TMP/sw.csv"
  [ ! -e "$TMP/sw.csv" ] && pass || { fail "sweep --set $sets: ran and wrote a CSV"; rm -f "$TMP/sw.csv"; }
done

# 6. monitor: a file of random bytes (seeded) gets an error of printable ASCII; a device
#    that never ends is refused at once (memory capped so a regression cannot take the
#    machine with it).
$PY -c "import random,sys; random.seed(25); sys.stdout.buffer.write(bytes(random.randrange(256) for _ in range(4096)))" \
  >"$TMP/random.vcd"
err="$("$BIN" monitor --signal "$TMP/random.vcd" -o "$TMP/m.png" 2>&1 >/dev/null)"; rc=$?
if [ $rc -ne 0 ] && [ $rc -lt 128 ] && [ -n "$err" ] && ! LC_ALL=C grep -q '[^ -~]' <<<"$err"; then pass
else fail "monitor on random bytes (rc $rc): the error is not printable ASCII: $(printf '%q' "$err")"; fi
err="$(ulimit -v 2000000; timeout 20 "$BIN" monitor --signal /dev/zero -o "$TMP/z.png" 2>&1 >/dev/null)"; rc=$?
[ $rc -ne 0 ] && [ $rc -lt 124 ] && grep -q "/dev/zero: not a regular file" <<<"$err" && pass ||
  fail "monitor --signal /dev/zero (rc $rc): $err"

echo "$passes passed, $fails failed"
[ "$fails" -eq 0 ]
