#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest -L apps: a real program's frames end to end (docs/workloads.md). Captures 3
# frames of glmark2's `build` scene at 96x72 (scripts/capture_glmark2: xvfb-run, llvmpipe,
# apitrace), imports them (rastsim import-apitrace), renders them, and compares every
# frame's coverage and depth with llvmpipe's replay of the capture
# (scripts/compare_llvmpipe): 0 pixels away from an edge may differ. Then the checks of
# the check below must fail. Textures: a hand-written dump's textured quad, rendered, its
# corner texels checked by hand (no tool needed); and 3 frames of glmark2's texture scene
# with a plain-lookup fragment shader (capture_glmark2 --plain-texture), imported with its
# texture, colour compared with llvmpipe's (nearest: equal away from edges and texel
# edges), and a wrong filter or a flipped t must fail that comparison.
# Exits 77 (skipped) without apitrace, glmark2 or xvfb-run.
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
# A textured quad by hand: a 2x2 RGBA texture, GL's first row (t = 0) red, green and its
# second blue, yellow, nearest; a strip over the whole 8x8 viewport with (s, t) = (0, 0)
# at GL's bottom-left corner (-1, -1). GL shows t = 0 at the bottom, so rastsim's image
# (row 0 the top) must have blue at its top-left pixel (0, 0), red at the bottom-left
# (0, 7), green at (7, 7), yellow at (7, 0).
python3 - "$TMP0" <<'PY'
import struct, sys
d = sys.argv[1]
open(d + "/blob_call5.bin", "wb").write(bytes([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 0, 255]))
open(d + "/blob_call20.bin", "wb").write(struct.pack("<12f", -1, -1, 0, 1, -1, 0, -1, 1, 0, 1, 1, 0))
open(d + "/blob_call23.bin", "wb").write(struct.pack("<8f", 0, 0, 1, 0, 0, 1, 1, 1))
vs = r"attribute vec3 position;\nattribute vec2 texcoord;\nuniform mat4 M;\nvarying vec2 tc;\n" \
     r"void main() { tc = texcoord; gl_Position = M * vec4(position, 1.0); }"
fs = r"uniform sampler2D t;\nvarying vec2 tc;\nvoid main() { gl_FragColor = texture2D(t, tc); }"
open(d + "/tex.dump", "w").write("""1 glViewport(x = 0, y = 0, width = 8, height = 8) // fake
2 glBindTexture(target = GL_TEXTURE_2D, texture = 7)
3 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_NEAREST)
4 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MAG_FILTER, param = GL_NEAREST)
5 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGBA, width = 2, height = 2, border = 0, format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = blob("blob_call5.bin"))
6 glCreateProgram() = 1
7 glCreateShader(type = GL_VERTEX_SHADER) = 2
8 glShaderSource(shader = 2, count = 1, string = &"%s", length = NULL)
9 glAttachShader(program = 1, shader = 2)
10 glCreateShader(type = GL_FRAGMENT_SHADER) = 3
11 glShaderSource(shader = 3, count = 1, string = &"%s", length = NULL)
12 glAttachShader(program = 1, shader = 3)
13 glBindAttribLocation(program = 1, index = 0, name = "position")
14 glBindAttribLocation(program = 1, index = 1, name = "texcoord")
15 glLinkProgram(program = 1)
16 glUseProgram(program = 1)
17 glGetUniformLocation(program = 1, name = "M") = 0
18 glUniformMatrix4fv(location = 0, count = 1, transpose = GL_FALSE, value = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})
19 glBindBuffer(target = GL_ARRAY_BUFFER, buffer = 1)
20 glBufferData(target = GL_ARRAY_BUFFER, size = 48, data = blob("blob_call20.bin"), usage = GL_STATIC_DRAW)
21 glVertexAttribPointer(index = 0, size = 3, type = GL_FLOAT, normalized = GL_FALSE, stride = 0, pointer = NULL)
22 glBindBuffer(target = GL_ARRAY_BUFFER, buffer = 2)
23 glBufferData(target = GL_ARRAY_BUFFER, size = 32, data = blob("blob_call23.bin"), usage = GL_STATIC_DRAW)
24 glVertexAttribPointer(index = 1, size = 2, type = GL_FLOAT, normalized = GL_FALSE, stride = 0, pointer = NULL)
25 glEnableVertexAttribArray(index = 0)
26 glEnableVertexAttribArray(index = 1)
27 glDrawArrays(mode = GL_TRIANGLE_STRIP, first = 0, count = 4)
28 glXSwapBuffers(dpy = 0x1, drawable = 2)
""" % (vs, fs))
PY
"$RASTSIM" import-apitrace --dump "$TMP0/tex.dump" -o "$TMP0/quad.trace" > "$TMP0/import.txt"
grep -q "1 textured (1 texture files)" "$TMP0/import.txt" || { cat "$TMP0/import.txt"; echo "FAIL: the quad was not imported textured"; exit 1; }
[ -s "$TMP0/quad.tex7.png" ] || { echo "FAIL: no texture file quad.tex7.png beside the trace"; exit 1; }
"$RASTSIM" render --scene "$TMP0/quad.trace" --set display.width=8 --set display.height=8 -o "$TMP0/quad.ppm" -q
python3 - "$TMP0/quad.ppm" <<'PY'
import sys
data = open(sys.argv[1], "rb").read().split(b"\n", 3)
px = data[3]
at = lambda x, y: tuple(px[3 * (y * 8 + x):3 * (y * 8 + x) + 3])
want = {(0, 0): (0, 0, 255), (0, 7): (255, 0, 0), (7, 7): (0, 255, 0), (7, 0): (255, 255, 0)}
got = {k: at(*k) for k in want}
assert got == want, "corner texels %s, want %s (GL's t = 0 at the bottom)" % (got, want)
print("apps: the hand-made textured quad's corners are GL's texels, t = 0 at the bottom")
PY
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
# Textures: 3 frames of glmark2's texture scene at 320x240 (a crate, nearest, clamp; its
# front face about 160 px wide for 512 texels: about 3 texels a pixel, where 96x72 would
# make it 16 and most pixels a texel edge) whose fragment shader is made a plain lookup,
# so rastsim's colours are the texture's alone.
"$SRC/scripts/capture_glmark2" --size 320x240 --plain-texture texture 3 "$TMP/tex.trace"
"$RASTSIM" import-apitrace "$TMP/tex.trace" -o "$TMP/tex.rs.trace" --config-out "$TMP/tex.set" | tee "$TMP/teximport.txt"
grep -q ": 3 frames, 3 draws (3 imported, 0 refused), 0 clears refused, 3 textured (1 texture files)" "$TMP/teximport.txt" \
  || { echo "FAIL: expected 3 textured draws and one texture file"; exit 1; }
"$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/tex.trace" --imported "$TMP/tex.rs.trace" \
  --set-file "$TMP/tex.set" --name texture --json "$TMP/texcmp.json" | tee "$TMP/texcmp.txt"
python3 - "$TMP/texcmp.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["totals"]
assert t["differ"] == 0 and t["colour_frames"] == 3, t
assert t["colour_compared"] > 1000 and t["colour_other"] == 0, t
print("apps: texture, %d pixels' colours compared, %d equal, %d at a texel edge" % (
    t["colour_compared"], t["colour_equal"], t["colour_edge"]))
PY
# Checks of the check: bilinear filtering where llvmpipe samples nearest, and t flipped
# (t -> 1 - t on every vertex, the image upside down), must each fail the colour comparison.
sed 's/^texfilter nearest$/texfilter bilinear/' "$TMP/tex.rs.trace" > "$TMP/texbil.trace"
if "$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/tex.trace" --imported "$TMP/texbil.trace" \
     --set-file "$TMP/tex.set" --frames 1 --name bilinear >/dev/null 2>&1; then
  echo "FAIL: the colour comparison passed with bilinear filtering"; exit 1
fi
awk '$1 == "tri4" && NF == 28 { for (k = 0; k < 3; ++k) $(10 + 9 * k) = 1 - $(10 + 9 * k) } { print }' \
  "$TMP/tex.rs.trace" > "$TMP/texflip.trace"
if "$SRC/scripts/compare_llvmpipe" --rastsim "$RASTSIM" --capture "$TMP/tex.trace" --imported "$TMP/texflip.trace" \
     --set-file "$TMP/tex.set" --frames 1 --name flipped >/dev/null 2>&1; then
  echo "FAIL: the colour comparison passed with t flipped"; exit 1
fi
echo "apps: bilinear filtering and a flipped t are caught"
