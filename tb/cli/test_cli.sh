#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# End-to-end checks of `rastsim render` and `rastsim config` as a user runs them.
# usage: test_cli.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"

SCENE="$SRC/traces/torus.trace"
CFG="$SRC/configs/default.toml"

# 1. The demo render writes an image and every documented stat.
if "$BIN" render --config "$CFG" --scene "$SCENE" --set raster.depth_func=less \
     -o "$TMP/a.png" --stats "$TMP/a.json" -q; then
  [ -s "$TMP/a.png" ] && pass || fail "render wrote no PNG"
  for k in triangles_in triangles_culled tiles_visited tiles_rejected tiles_accepted tiles_partial \
           pixel_tests fragments framebuffer_crc32 wall_seconds; do
    json_field "$TMP/a.json" "$k" >/dev/null 2>&1 && pass || fail "stats lack $k"
  done
else
  fail "render of the demo scene failed"
fi

# 1b. The stats JSON gives framebuffer_crc32 as the summary line prints it (8 hex digits).
line="$("$BIN" render --config "$CFG" --scene "$SCENE" --stats "$TMP/crc.json")"
crc_json="$(json_field "$TMP/crc.json" framebuffer_crc32)"
if [[ "$crc_json" =~ ^[0-9a-f]{8}$ ]] && grep -q "crc32 $crc_json," <<<"$line"; then pass
else fail "framebuffer_crc32 '$crc_json' is not the summary line's crc32: $line"; fi

# 2. The tile size changes the tile counts but never the image.
crc0=""; tiles_seen=""
for t in 2 4 8 16 32 64 128; do
  "$BIN" render --config "$CFG" --scene "$SCENE" --set raster.depth_func=less \
    --set raster.tile_size=$t --stats "$TMP/t$t.json" -q || { fail "render tile_size=$t"; continue; }
  crc="$(json_field "$TMP/t$t.json" framebuffer_crc32)"
  tiles="$(json_field "$TMP/t$t.json" tiles_visited)"
  [ -z "$crc0" ] && crc0="$crc"
  [ "$crc" = "$crc0" ] && pass || fail "tile_size=$t changed the image crc ($crc vs $crc0)"
  tiles_seen="$tiles_seen $tiles"
done
[ "$(tr ' ' '\n' <<<"$tiles_seen" | sort -u | grep -c .)" -ge 6 ] && pass || fail "tile counts did not change:$tiles_seen"

# 3. PPM output.
"$BIN" render --config "$CFG" --scene "$SCENE" -o "$TMP/a.ppm" -q && head -c 2 "$TMP/a.ppm" | grep -q P6 && pass || fail "PPM output"

# 4. Bad input: one clear line naming file, line and what is wrong; never a crash.
printf '[raster]\ntile_size = 24\n' > "$TMP/bad_range.toml"
expect_error "tile size not a power of two" "bad_range.toml:2: raster.tile_size = 24 is not allowed.*power of two" -- \
  "$BIN" render --config "$TMP/bad_range.toml" --scene "$SCENE"
printf '[raster]\ntile_sise = 16\n' > "$TMP/bad_key.toml"
expect_error "unknown key" "bad_key.toml:2: unknown key 'raster.tile_sise'" -- \
  "$BIN" render --config "$TMP/bad_key.toml" --scene "$SCENE"
printf '[display]\nwidth = "wide"\n' > "$TMP/bad_type.toml"
expect_error "wrong type" "bad_type.toml:2: display.width must be an integer" -- \
  "$BIN" render --config "$TMP/bad_type.toml" --scene "$SCENE"
printf '[display\nwidth = 3\n' > "$TMP/bad_toml.toml"
expect_error "TOML syntax" "bad_toml.toml:1:" -- "$BIN" render --config "$TMP/bad_toml.toml" --scene "$SCENE"
expect_error "unknown --set key" "unknown key 'raster.nope'" -- "$BIN" render --scene "$SCENE" --set raster.nope=1
expect_error "bad --set enum" "raster.cull.*one of none, back, front" -- "$BIN" render --scene "$SCENE" --set raster.cull=sideways
expect_error "viewport too big for the format" "does not fit in raster.coord_format s7.16" -- \
  "$BIN" render --scene "$SCENE" --set display.width=400
printf 'viewport 128 128\ntri 0 0 10 0 0 zz\n' > "$TMP/bad.trace"
expect_error "malformed trace" "bad.trace:2:" -- "$BIN" render --scene "$TMP/bad.trace"
printf 'tri 0 0 500 0 0 10\n' > "$TMP/far.trace"
expect_error "vertex outside the format" "far.trace:1: vertex 1 .*outside the s7.16 coordinate range" -- \
  "$BIN" render --scene "$TMP/far.trace"
"$BIN" render --scene "$TMP/far.trace" --set raster.out_of_range=cull --stats "$TMP/far.json" -q && \
  [ "$(json_field "$TMP/far.json" triangles_out_of_range)" = 1 ] && pass || fail "out_of_range=cull"
expect_error "missing scene" "" -- "$BIN" render --scene "$TMP/none.trace"
# Traversal methods: the RTL walks tiles only, so cosim refuses the others by name.
expect_error "cosim with bbox traversal" "raster.traversal = bbox has no RTL" -- \
  "$BIN" cosim --scene "$SCENE" --set raster.traversal=bbox
expect_error "bad hier_levels" "raster.hier_levels .*powers of two" -- \
  "$BIN" render --scene "$SCENE" --set raster.hier_levels=16/64 -o "$TMP/h.png"
# A sweep over the methods: scanline's own counters get a column although the first row
# (tiled) does not report them; empty there, a number in the scanline row.
"$BIN" sweep --scene "$SRC/traces/state.trace" --set raster.traversal=tiled,scanline \
  --set raster.scanline_arith=f32 --out "$TMP/methods.csv" >/dev/null 2>&1 &&
  /usr/bin/python3 - "$TMP/methods.csv" <<'PY' && pass || fail "sweep keeps columns of later rows"
import csv, sys
rows = {r["raster.traversal"]: r for r in csv.DictReader(open(sys.argv[1]))}
assert rows["tiled"]["pixels_wrong"] == "" and rows["scanline"]["pixels_wrong"].isdigit(), rows
PY

# 4a. sweep --resume: a CSV cut to its header and some rows, or a sweep killed mid-way
#     (every finished row already in the CSV), resumed, equals an uninterrupted sweep
#     apart from wall times, running only the missing rows; a CSV of other columns is refused.
"$SRC/scripts/gen_torus" --rings 256 --sides 128 > "$TMP/big.trace"
SW=(sweep --scene "$TMP/big.trace" --scene "$SRC/traces/state.trace" --set raster.tile_size=4,8,16,32,64
    --set raster.traversal=tiled,scanline --set raster.scanline_arith=f32 -j1)
if "$BIN" "${SW[@]}" --out "$TMP/full.csv" 2>/dev/null; then
  head -n 8 "$TMP/full.csv" > "$TMP/cut.csv"
  "$BIN" "${SW[@]}" --out "$TMP/cut.csv" --resume 2>"$TMP/cut.err" && grep -q "7 of 20 rows already" "$TMP/cut.err" &&
    "$SRC/tb/cli/compare_sweeps.py" "$TMP/full.csv" "$TMP/cut.csv" && pass || fail "sweep --resume of a cut CSV"
  rm -f "$TMP/killed.csv"
  "$BIN" "${SW[@]}" --out "$TMP/killed.csv" 2>/dev/null & pid=$!
  for _ in $(seq 500); do [ "$(cat "$TMP/killed.csv" 2>/dev/null | wc -l)" -ge 4 ] && break; sleep 0.01; done
  kill -TERM $pid; wait $pid; rc=$?
  rows=$(($(wc -l < "$TMP/killed.csv") - 1))
  [ $rc -eq 143 ] && [ $rows -ge 3 ] && [ $rows -lt 20 ] && pass || fail "sweep not killed mid-way (rc $rc, $rows rows)"
  sleep 0.2; pgrep -f "$TMP/big.trace" >/dev/null && fail "a killed sweep left simulations running" || pass
  "$BIN" "${SW[@]}" --out "$TMP/killed.csv" --resume 2>"$TMP/killed.err" && grep -q "$rows of 20 rows already" "$TMP/killed.err" &&
    "$SRC/tb/cli/compare_sweeps.py" "$TMP/full.csv" "$TMP/killed.csv" && pass || fail "sweep --resume after a kill"
else
  fail "sweep for the --resume checks"
fi
# 4a'. The row key holds the level (--level, +area with --area), which changes the columns:
#     SystemC rows are not taken as done by a cosim sweep (they run, with cycles_rtl, and the
#     SystemC rows stay as foreign rows), and the other way round; rows marked systemc+area
#     count for --area only. embedded.toml runs on its shipped RTL model (no build).
LV=(sweep --config "$SRC/configs/embedded.toml" --scene "$SRC/traces/primitives.trace" --set raster.cull=none,back -j1)
rm -f "$TMP/lvl.csv"
"$BIN" "${LV[@]}" --out "$TMP/lvl.csv" 2>/dev/null && pass || fail "systemc sweep for the level checks"
"$BIN" "${LV[@]}" --out "$TMP/lvl.csv" --level cosim --resume 2>"$TMP/lvl.err" &&
  grep -q "0 of 2 rows already" "$TMP/lvl.err" && pass || fail "cosim resume took systemc rows: $(cat "$TMP/lvl.err")"
/usr/bin/python3 - "$TMP/lvl.csv" <<'PY' && pass || fail "CSV after resuming at another level"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["level"] for r in rows] == ["cosim", "cosim", "systemc", "systemc"], rows
for r in rows:
    assert r["status"] == "ok", r
    assert (r["cycles_rtl"] != "") == (r["level"] == "cosim"), r
PY
for level in cosim systemc; do
  "$BIN" "${LV[@]}" --out "$TMP/lvl.csv" --level $level --resume 2>"$TMP/lvl.err" &&
    grep -q "2 of 2 rows already" "$TMP/lvl.err" && pass || fail "resume --level $level: $(cat "$TMP/lvl.err")"
done
# Only systemc+area rows (made by hand: a real --area run synthesises, ctest -L area does that).
/usr/bin/python3 - "$TMP/lvl.csv" "$TMP/lvl_area.csv" <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["level"] == "systemc"]
w = csv.DictWriter(open(sys.argv[2], "w", newline=""), fieldnames=list(rows[0]), lineterminator="\n")
w.writeheader()
for r in rows:
    w.writerow(dict(r, level="systemc+area"))
PY
cp "$TMP/lvl_area.csv" "$TMP/lvl_area2.csv"
"$BIN" "${LV[@]}" --out "$TMP/lvl_area.csv" --area --resume 2>"$TMP/lvl.err" &&
  grep -q "2 of 2 rows already" "$TMP/lvl.err" && ! grep -q "sweep: area" "$TMP/lvl.err" && pass ||
  fail "resume --area of systemc+area rows: $(cat "$TMP/lvl.err")"
"$BIN" "${LV[@]}" --out "$TMP/lvl_area2.csv" --resume 2>"$TMP/lvl.err" &&
  grep -q "0 of 2 rows already" "$TMP/lvl.err" && pass || fail "plain resume took systemc+area rows: $(cat "$TMP/lvl.err")"
expect_error "resume with other swept keys" "needs a CSV of this sweep's columns" -- \
  "$BIN" sweep --scene "$SRC/traces/state.trace" --set raster.tile_size=8,16 --out "$TMP/full.csv" --resume
for opt in --resume --backend --slurm-partition --slurm-time --slurm-workdir --slurm-arg --slurm-poll; do
  "$BIN" sweep --help | grep -q -- "$opt" && pass || fail "sweep --help lacks $opt"
done

# 4b. Compressed scenes (gzip always; zstd when its tool is installed) render the plain
# scene's image, and a broken one is a clear error naming the file.
"$BIN" render --scene "$SCENE" --stats "$TMP/plain.json" -q || fail "plain render for the compressed check"
crc_plain="$(json_field "$TMP/plain.json" framebuffer_crc32 2>/dev/null)"
gzip -c "$SCENE" > "$TMP/torus.trace.gz"
zips=("$TMP/torus.trace.gz")
if command -v zstd >/dev/null; then zstd -q -c "$SCENE" > "$TMP/torus.trace.zst"; zips+=("$TMP/torus.trace.zst"); fi
for z in "${zips[@]}"; do
  if "$BIN" render --scene "$z" --stats "$TMP/z.json" -q; then
    [ "$(json_field "$TMP/z.json" framebuffer_crc32)" = "$crc_plain" ] && pass || fail "$z: crc differs from the plain scene"
  else
    fail "render --scene $z"
  fi
done
head -c 200 "$TMP/torus.trace.gz" > "$TMP/cut.trace.gz"
expect_error "truncated gzip scene" "cut.trace.gz: truncated gzip data" -- "$BIN" render --scene "$TMP/cut.trace.gz"
printf 'viewport 64 64\ntri 0 0 10 0 0 zz\n' | gzip -c > "$TMP/badline.trace.gz"
expect_error "error line in a gzip scene" "badline.trace.gz:2:" -- "$BIN" render --scene "$TMP/badline.trace.gz"

# 6. estimate: bounds and per-stage busy in the stats, lower <= estimate <= upper; a bad
#    config is one error line naming the file and line. The shipped config models DRAM:
#    there the upper bound is null and the bandwidth bound is part of the lower; with
#    memory.model = fixed both bounds hold.
for mem in dram fixed; do
  if "$BIN" estimate --config "$CFG" --scene "$SCENE" --set memory.model=$mem --stats "$TMP/e.json" -q; then
    for k in cycles_lower_bound cycles_upper_bound cycles_estimate bandwidth_lower_bound wall_seconds; do
      json_field "$TMP/e.json" "$k" >/dev/null 2>&1 && pass || fail "estimate ($mem) stats lack $k"
    done
    /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); up=j['cycles_upper_bound']
assert j['cycles_lower_bound'] <= j['cycles_estimate'], j
assert (up is None) == (sys.argv[2] == 'dram') and (up is None or j['cycles_estimate'] <= up), j
assert (j['bandwidth_lower_bound'] > 0) == (sys.argv[2] == 'dram'), j
assert j['stages']['rop']['busy'] > 0" "$TMP/e.json" $mem && pass || fail "estimate ($mem) bounds out of order"
  else
    fail "estimate of the demo scene ($mem) failed"
  fi
done
"$BIN" estimate --help | grep -q -- "cycles_upper_bound" && pass || fail "estimate --help"
printf '[fine]\nsamples_per_cycle = 0\n' > "$TMP/bad_est.toml"
expect_error "estimate bad config" "bad_est.toml:2:.*samples_per_cycle" -- "$BIN" estimate --config "$TMP/bad_est.toml" --scene "$SCENE"
expect_error "estimate missing scene" "scene" -- "$BIN" estimate --config "$CFG" --scene "$TMP/none.trace"

# 5. --help on every command; config --doc lists the keys.
for c in render config; do "$BIN" $c --help | grep -q -- "--set" && pass || fail "$c --help"; done
"$BIN" config --doc | grep -q "raster.tile_size" && pass || fail "config --doc"
"$BIN" config --doc | grep -q "raster.traversal = \"tiled\"" && pass || fail "config --doc traversal"

# 6. Where the cycles go: simulate --timeline writes trace-event JSON with a track per
# stage and FIFO, --heatmap a PNG (with --heatmap-data's per-tile cycles summing to the
# attributed stages' busy cycles), --help lists both, and an unwritable path is a clear
# error before the simulation.
if "$BIN" simulate --config "$CFG" --scene "$SCENE" --timeline "$TMP/t.json" --heatmap "$TMP/h.png" \
     --heatmap-data "$TMP/h.json" --stats "$TMP/s.json" -q; then
  /usr/bin/python3 - "$TMP/t.json" "$TMP/s.json" "$TMP/h.json" <<'PY' && pass || fail "timeline/heatmap contents"
import json, sys
t, s, h = (json.load(open(p)) for p in sys.argv[1:4])
names = {e["args"]["name"] for e in t["traceEvents"] if e["ph"] == "M" and e["name"] == "thread_name"}
assert set(s["stages"]) <= names, names
assert all(any(n.startswith(f + " ") for n in names) for f in s["fifos"]), names
assert any(e["ph"] == "X" for e in t["traceEvents"]) and any(e["ph"] == "C" for e in t["traceEvents"])
assert s["timeline"]["events"] == sum(1 for _ in t["traceEvents"])
for name, st in h["stages"].items():
    assert sum(st["tiles"]) + st["unattributed"] == s["stages"][name]["busy"], name
PY
  head -c 8 "$TMP/h.png" | od -An -c | grep -q "P   N   G" && pass || fail "heatmap is not a PNG"
else
  fail "simulate --timeline --heatmap failed"
fi
"$BIN" simulate --config "$CFG" --scene "$SCENE" --heatmap "$TMP/r.png" --heatmap-stage rop -q && [ -s "$TMP/r.png" ] \
  && pass || fail "--heatmap-stage rop"
expect_error "unwritable timeline" "nope/t.json: cannot open for writing" -- \
  "$BIN" simulate --config "$CFG" --scene "$SCENE" --timeline "$TMP/nope/t.json" -q
expect_error "bad heatmap stage" "heatmap-stage" -- \
  "$BIN" simulate --config "$CFG" --scene "$SCENE" --heatmap "$TMP/x.png" --heatmap-stage nosuch -q
for o in --timeline --heatmap --heatmap-stage; do
  "$BIN" simulate --help | grep -q -- "$o" && pass || fail "simulate --help lacks $o"
done

# 7. Multisampling at the timed level: simulate --set raster.samples=4 (msaa and ssaa)
# writes the image render writes (same CRC, from the resolved buffer), the resolve pass's
# cycles and the ROP's traffic; a 2D scene with samples is the reference model's error.
for mode in msaa ssaa; do
  if "$BIN" render --config "$CFG" --scene "$SCENE" --set raster.samples=4 --set raster.aa_mode=$mode \
       --stats "$TMP/ms_r.json" -q &&
     "$BIN" simulate --config "$CFG" --scene "$SCENE" --set raster.samples=4 --set raster.aa_mode=$mode \
       -o "$TMP/ms.png" --stats "$TMP/ms_s.json" -q; then
    [ "$(json_field "$TMP/ms_s.json" framebuffer_crc32)" = "$(json_field "$TMP/ms_r.json" framebuffer_crc32)" ] \
      && pass || fail "simulate samples=4 $mode: CRC differs from render"
    [ -s "$TMP/ms.png" ] && pass || fail "simulate samples=4 $mode wrote no image"
    for k in samples sample_tests samples_covered pixels_partially_covered resolve_bytes rop_accesses \
             framebuffer_bytes resolve_cycles; do
      json_field "$TMP/ms_s.json" "$k" >/dev/null 2>&1 && pass || fail "simulate samples=4 $mode stats lack $k"
    done
    [ "$(json_field "$TMP/ms_s.json" resolve_cycles)" -gt 0 ] && pass || fail "simulate samples=4: no resolve cycles"
  else
    fail "simulate --set raster.samples=4 --set raster.aa_mode=$mode failed"
  fi
done
expect_error "2D with samples" "raster.samples = 4" -- \
  "$BIN" simulate --scene "$SRC/traces/2d/test_card.trace" --set raster.samples=4 -q

# 8. coverage-error: the JSON keys per sample count, the mean falling from 1 to 16 samples
#    on a near-horizontal scene, a bad count and a scanline traversal refused; --help.
if "$BIN" coverage-error --config "$CFG" --scene "$SRC/traces/aa/near_horizontal.trace" --samples 1,4,16 \
     --stats "$TMP/ce.json" -q; then
  /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1]))['samples']
for n in ('1', '4', '16'):
    for k in ('edge_pixels', 'coverage_error_mean', 'coverage_error_rms', 'coverage_error_max'):
        assert k in j[n], (n, k)
assert j['1']['edge_pixels'] == j['16']['edge_pixels'] > 0, j
assert j['1']['coverage_error_mean'] > j['4']['coverage_error_mean'] > j['16']['coverage_error_mean'], j" \
    "$TMP/ce.json" && pass || fail "coverage-error stats"
else
  fail "coverage-error of near_horizontal failed"
fi
expect_error "coverage-error bad count" "--samples 3" -- "$BIN" coverage-error --scene "$SRC/traces/aa/thin.trace" --samples 3
expect_error "coverage-error scanline" "exact traversal" -- \
  "$BIN" coverage-error --scene "$SRC/traces/aa/thin.trace" --samples 4 --set raster.traversal=scanline
for o in --samples --stats --scene --config --set --quiet; do
  "$BIN" coverage-error --help | grep -q -- "$o" && pass || fail "coverage-error --help lacks $o"
done

# obj_ignored follows the camera: a perspective camera draws OBJ `l` and `p`, ortho skips
# them (scene.obj_lines_points = skip) and lists them.
OBJ_LP="$SRC/fuzz/corpus/obj/perspective.obj"
got=$("$BIN" render --scene "$OBJ_LP" --set scene.camera=perspective --stats - -q 2>/dev/null | python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)["obj_ignored"], sort_keys=True))')
[ "$got" = '{"vn": 1}' ] && pass || fail "perspective obj_ignored: $got"
got=$("$BIN" render --scene "$OBJ_LP" --set scene.obj_lines_points=skip --stats - -q 2>/dev/null | python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)["obj_ignored"], sort_keys=True))')
[ "$got" = '{"l": 2, "p": 1, "vn": 1}' ] && pass || fail "ortho obj_ignored: $got"

echo "cli: $passes passed, $fails failed"
[ $fails -eq 0 ]
