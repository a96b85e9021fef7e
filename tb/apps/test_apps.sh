#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest -L apps: a real program's frames end to end (docs/workloads.md). Captures 3
# frames of glmark2's `build` scene at 96x72 (scripts/capture_glmark2: xvfb-run, llvmpipe,
# apitrace), imports them (rastsim import-apitrace), renders them, and compares every
# frame's coverage and depth with llvmpipe's replay of the capture
# (scripts/compare_llvmpipe): 0 pixels away from an edge may differ. Then the checks of
# the check below must fail. Exits 77 (skipped) without apitrace, glmark2 or xvfb-run.
# usage: test_apps.sh RASTSIM SOURCE_DIR
set -euo pipefail
RASTSIM="$1"; SRC="$2"
# Without any tool: a malformed dump line is a file:line error, and the bad capture's.
TMP0="$(mktemp -d)"
printf '// process.name = "x"\n1 glViewport(x = 0, y = 0, width = 8, height = 8)\n2 glClear(mask = \n' > "$TMP0/bad.dump"
if "$RASTSIM" import-apitrace --dump "$TMP0/bad.dump" -o "$TMP0/out.trace" 2> "$TMP0/err.txt"; then
  echo "FAIL: a malformed dump was accepted"; exit 1
fi
grep -q "bad.dump:3: missing value (column 18)" "$TMP0/err.txt" || { cat "$TMP0/err.txt"; echo "FAIL: no file:line error"; exit 1; }
rm -rf "$TMP0"
for tool in apitrace glretrace glmark2 xvfb-run; do
  command -v "$tool" >/dev/null || { echo "skip: '$tool' not installed (scripts/setup.sh installs it)"; exit 77; }
done
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
"$SRC/scripts/capture_glmark2" --size 96x72 build 3 "$TMP/build.trace"
"$RASTSIM" import-apitrace "$TMP/build.trace" -o "$TMP/build.rs.trace.zst" --config-out "$TMP/build.set" | tee "$TMP/import.txt"
grep -q ": 3 frames, 3 draws (3 imported, 0 refused)" "$TMP/import.txt" || { echo "FAIL: expected 3 frames, 3 draws imported"; exit 1; }
mapfile -t SETS < <(sed 's/^/--set\n/' "$TMP/build.set")
"$RASTSIM" render --config "$SRC/configs/d3d11.toml" --set display.width=96 --set display.height=72 "${SETS[@]}" \
  --scene "$TMP/build.rs.trace.zst" -o "$TMP/out_%04d.png" --stats "$TMP/stats.json" -q
for k in 0 1 2; do [ -s "$TMP/out_000$k.png" ] || { echo "FAIL: frame $k not rendered"; exit 1; }; done
"$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/build.trace" --imported "$TMP/build.rs.trace.zst" \
  --set-file "$TMP/build.set" --name build --json "$TMP/cmp.json" | tee "$TMP/cmp.txt"
python3 - "$TMP/cmp.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["totals"]
assert t["frames_compared"] == 3, t
assert t["compared"] > 5000 and t["depth_compared"] > 500, t  # the bunny-free build model fills part of 96x72
assert t["differ"] == 0, t
print("apps: 3 frames, %d pixels compared, %d near an edge, 0 differ" % (t["compared"], t["near"]))
PY
# Checks of the check. (1) Snapping to a quarter pixel (s15.2) must change coverage away
# from the edges. (2) Front faces taken as clockwise: rastsim culls the faces llvmpipe
# draws and draws the back ones, the same silhouette of a closed mesh, so coverage agrees,
# but depth must fail a tolerance of 2^16 x 2^-24 (2^-8) that the true run passes (its
# differences are the vertex snapping's, docs/workloads.md).
if "$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/build.trace" --imported "$TMP/build.rs.trace.zst" \
     --set-file "$TMP/build.set" --set raster.coord_format=s15.2 --frames 1 --name s15.2 >/dev/null 2>&1; then
  echo "FAIL: the comparison passed with quarter-pixel snapping"; exit 1
fi
"$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/build.trace" --imported "$TMP/build.rs.trace.zst" \
  --set-file "$TMP/build.set" --depth-tolerance 65536 --name build >/dev/null
sed 's/raster.front_face=ccw/raster.front_face=cw/' "$TMP/build.set" > "$TMP/flipped.set"
if "$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/build.trace" --imported "$TMP/build.rs.trace.zst" \
     --set-file "$TMP/flipped.set" --depth-tolerance 65536 --frames 1 --name flipped >/dev/null 2>&1; then
  echo "FAIL: the comparison passed with the front face flipped"; exit 1
fi
echo "apps: quarter-pixel snapping and the flipped front face are caught"
