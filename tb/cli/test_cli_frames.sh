#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Multi-frame traces end to end (docs/trace-format.md "Frames"): -o out_%04d.png, frames[],
# --frames A:B against the full run (images byte for byte, simulate's cycles for 0:N, the
# estimate's per-frame work), the range and pattern errors, --frame-sample 1 = the full run,
# cosim's frames[] and --frames (0 mismatches a frame), --tolerance choosing frame sampling,
# scan-out flipping at vertical blank (three solid frames shown whole and in order).
# usage: test_cli_frames.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"

CFG="$SRC/configs/default.toml"
SEQ="$TMP/spin.trace"
/usr/bin/python3 "$SRC/scripts/gen_spin" --torus --frames 6 --size 128x128 --zoom 0.4 --pulse 3 -o "$SEQ" \
  || { echo "FAIL: gen_spin"; exit 1; }
field() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }

# 1. One image a frame; frames[] of 6 whose counts sum to the run's; the last image is the run's.
mkdir -p "$TMP/all" "$TMP/part"
"$BIN" render --config "$CFG" --scene "$SEQ" -o "$TMP/all/f_%02d.png" --stats "$TMP/all.json" -q || fail "render frames"
[ "$(ls "$TMP/all" | wc -l)" = 6 ] && pass || fail "render wrote $(ls "$TMP/all" | wc -l) images, not 6"
[ "$(field "$TMP/all.json" "len(j['frames'])")" = 6 ] && pass || fail "frames[] is not 6 long"
[ "$(field "$TMP/all.json" "sum(f['fragments'] for f in j['frames']) == j['fragments']")" = True ] && pass \
  || fail "per-frame fragments do not sum to the run's"
[ "$(field "$TMP/all.json" "j['frames'][-1]['framebuffer_crc32'] == j['framebuffer_crc32']")" = True ] && pass \
  || fail "the last frame's crc is not the run's"

# 2. --frames 2:4 writes frames 2 and 3, byte for byte the full run's.
"$BIN" render --config "$CFG" --scene "$SEQ" --frames 2:4 -o "$TMP/part/f_%02d.png" --stats "$TMP/part.json" -q \
  || fail "render --frames 2:4"
[ "$(ls "$TMP/part")" = "$(printf 'f_02.png\nf_03.png')" ] && pass || fail "--frames 2:4 wrote $(ls "$TMP/part")"
for k in 02 03; do cmp -s "$TMP/all/f_$k.png" "$TMP/part/f_$k.png" && pass || fail "frame $k differs from the full run"; done
[ "$(field "$TMP/part.json" "j['frames_range']")" = "[2, 4]" ] && pass || fail "frames_range"

# 3. simulate: frames[].cycles sum to cycles; --frames 0:6 is the full run to the cycle;
#    --frames 3:5 draws the full run's frame 4 (simulate checks its CRC against the replay).
"$BIN" simulate --config "$CFG" --scene "$SEQ" --stats "$TMP/sim.json" -q || fail "simulate"
[ "$(field "$TMP/sim.json" "sum(f['cycles'] for f in j['frames']) == j['cycles']")" = True ] && pass \
  || fail "frames[].cycles do not sum to cycles"
"$BIN" simulate --config "$CFG" --scene "$SEQ" --frames 0:6 --stats "$TMP/sim06.json" -q || fail "simulate --frames 0:6"
[ "$(json_field "$TMP/sim06.json" cycles)" = "$(json_field "$TMP/sim.json" cycles)" ] && pass \
  || fail "--frames 0:6 cycles $(json_field "$TMP/sim06.json" cycles) != $(json_field "$TMP/sim.json" cycles)"
"$BIN" simulate --config "$CFG" --scene "$SEQ" --frames 3:5 --stats "$TMP/sim35.json" -q || fail "simulate --frames 3:5"
[ "$(field "$TMP/sim35.json" "j['framebuffer_crc32']")" = "$(field "$TMP/all.json" "j['frames'][4]['framebuffer_crc32']")" ] \
  && pass || fail "simulate --frames 3:5 image is not the full run's frame 4"

# 4. estimate --frames 1:3: each frame's analytic work equals the whole walk's.
"$BIN" estimate --config "$CFG" --scene "$SEQ" --stats "$TMP/est.json" -q || fail "estimate"
"$BIN" estimate --config "$CFG" --scene "$SEQ" --frames 1:3 --stats "$TMP/est13.json" -q || fail "estimate --frames"
[ "$(field "$TMP/est13.json" "[f['stages'] for f in j['frames']]")" = "$(field "$TMP/est.json" "[f['stages'] for f in j['frames'][1:3]]")" ] \
  && pass || fail "estimate --frames 1:3 per-frame busy differs from the whole walk's"

# 5. --frame-sample 1 simulates every frame: the full run's cycles, zero width.
"$BIN" simulate --config "$CFG" --scene "$SEQ" --frame-sample 1 --stats "$TMP/fs.json" -q || fail "--frame-sample 1"
[ "$(json_field "$TMP/fs.json" cycles)" = "$(json_field "$TMP/sim.json" cycles)" ] && pass || fail "--frame-sample 1 cycles"
[ "$(json_field "$TMP/fs.json" fidelity_level)" = frame-sampled ] && pass || fail "fidelity_level"

# 6. cosim: frames[] a frame (RTL and SystemC cycles, mismatches); --frames 2:5 starts the
#    RTL and the SystemC model from the reference's frame 1 and must end on the full
#    render's frame 4; the SystemC side's per-frame cycles equal simulate's at command
#    fetch (frames[].cycles_fetch: cosim splits both sides at fetch, where the RTL
#    testbench sees its commands start; simulate's frames[].cycles are at the ROP).
#    No --pulse: with memory.model = dram (as shipped) the RTL co-simulates no 2D command.
SEQC="$TMP/spinc.trace"
/usr/bin/python3 "$SRC/scripts/gen_spin" --torus --frames 6 --size 128x128 --zoom 0.4 -o "$SEQC" || fail "gen_spin (cosim)"
"$BIN" simulate --config "$CFG" --scene "$SEQC" --stats "$TMP/simc.json" -q || fail "simulate (cosim sequence)"
"$BIN" render --config "$CFG" --scene "$SEQC" --stats "$TMP/renc.json" -q || fail "render (cosim sequence)"
"$BIN" cosim --config "$CFG" --scene "$SEQC" --stats "$TMP/co.json" -q || fail "cosim (6 frames)"
[ "$(field "$TMP/co.json" "[f['mismatches'] for f in j['frames']]")" = "[0, 0, 0, 0, 0, 0]" ] && pass \
  || fail "cosim frames[].mismatches: $(field "$TMP/co.json" "[f['mismatches'] for f in j['frames']]")"
[ "$(field "$TMP/co.json" "[f['cycles_model'] for f in j['frames']]")" = "$(field "$TMP/simc.json" "[f['cycles_fetch'] for f in j['frames']]")" ] \
  && pass || fail "cosim frames[].cycles_model differ from simulate's frames[].cycles_fetch"
[ "$(field "$TMP/co.json" "sum(f['cycles_rtl'] for f in j['frames']) == j['cycles_rtl']")" = True ] && pass \
  || fail "cosim frames[].cycles_rtl do not sum to cycles_rtl"
[ "$(field "$TMP/co.json" "all(abs(f['cycle_error']) < 0.05 and f['cycles_rtl'] > 0 for f in j['frames'])")" = True ] \
  && pass || fail "cosim per-frame cycles: RTL and SystemC more than 5 % apart"
"$BIN" cosim --config "$CFG" --scene "$SEQC" --frames 2:5 --stats "$TMP/co25.json" -q || fail "cosim --frames 2:5"
[ "$(field "$TMP/co25.json" "[(f['frame'], f['mismatches']) for f in j['frames']]")" = "[(2, 0), (3, 0), (4, 0)]" ] \
  && pass || fail "cosim --frames 2:5 frames[]: $(field "$TMP/co25.json" "[(f['frame'], f['mismatches']) for f in j['frames']]")"
[ "$(field "$TMP/co25.json" "j['framebuffer_crc32_rtl']")" = "$(field "$TMP/renc.json" "j['frames'][4]['framebuffer_crc32']")" ] \
  && pass || fail "cosim --frames 2:5: the RTL's image is not the full render's frame 4"
#    Frames that do not clear: frame 2 alone draws over frames 0 and 1, so the RTL must
#    start from their framebuffer to end on the full render's last image.
KEEP="$TMP/keep.trace"
printf '%s\n' "viewport 128 128" "clear 0 0 0" "color 255 0 0" "tri 0 0 64 0 0 64" "frame" \
  "color 0 255 0" "tri 127 127 64 127 127 64" "frame" "color 0 0 255" "tri 0 127 20 100 40 127" > "$KEEP"
"$BIN" render --config "$CFG" --scene "$KEEP" --stats "$TMP/keep.json" -q || fail "render keep"
"$BIN" cosim --config "$CFG" --scene "$KEEP" --frames 2:3 --stats "$TMP/cokeep.json" -q || fail "cosim --frames 2:3 (no clears)"
[ "$(field "$TMP/cokeep.json" "j['framebuffer_crc32_rtl']")" = "$(field "$TMP/keep.json" "j['framebuffer_crc32']")" ] \
  && pass || fail "cosim --frames 2:3 did not start from frames 0..1's framebuffer"

# 7. --tolerance on a multi-frame trace answers with frame sampling (analytic bounds wider
#    than P), fewer frames than the trace, an interval covering the full run's cycles. P is
#    15 %: with each chosen frame warmed by its whole predecessor the sampled level's interval
#    on this sequence is 11.8 % at F = 0.095 (9 frames measured, 8 warm).
SEQ20="$TMP/spin20.trace"
/usr/bin/python3 "$SRC/scripts/gen_spin" --torus --frames 20 --size 128x128 --zoom 0.4 --pulse 5 -o "$SEQ20" \
  || fail "gen_spin 20"
"$BIN" simulate --config "$CFG" --scene "$SEQ20" --stats "$TMP/full20.json" -q || fail "simulate 20 frames"
"$BIN" simulate --config "$CFG" --scene "$SEQ20" --tolerance 15% --stats "$TMP/tol20.json" -q || fail "--tolerance 15%"
[ "$(json_field "$TMP/tol20.json" fidelity_level)" = frame-sampled ] && pass \
  || fail "--tolerance on 20 frames answered $(json_field "$TMP/tol20.json" fidelity_level): $(json_field "$TMP/tol20.json" fidelity_reason)"
[ "$(field "$TMP/tol20.json" "j['frames_total'] == 20 and j['frames_simulated'] < 20 and j['cycles_error_bound'] <= 0.15")" = True ] \
  && pass || fail "--tolerance frames_total / frames_simulated / cycles_error_bound"
FULL20=$(json_field "$TMP/full20.json" cycles)
[ "$(field "$TMP/tol20.json" "j['cycles_ci_low'] <= $FULL20 <= j['cycles_ci_high']")" = True ] && pass \
  || fail "--tolerance interval does not cover the full run's $FULL20 cycles"

# 8. scanout of three frames of solid red, green, blue (each clears and draws 16
#    full-screen triangles in its own colour): flips at vertical blank, every decoded
#    display period one whole frame, in order (never a mix). At a 1 MHz core a frame takes
#    about 2.5 periods, so the initial buffer and each frame repeat; untimed, each frame
#    flips at the next blank: periods [0, 1, 2].
RGB="$TMP/rgb.trace"
{
  echo "viewport 128 128"
  for c in "255 0 0" "0 255 0" "0 0 255"; do
    echo "clear $c"; echo "color $c"
    for i in 1 2 3 4 5 6 7 8; do echo "tri 0 0 128 0 0 128"; echo "tri 128 0 128 128 0 128"; done
    echo "frame"
  done
} > "$RGB"
"$BIN" scanout --config "$CFG" --set clock.core_mhz=1 --scene "$RGB" --timed -o "$TMP/scan_%02d.ppm" \
  --stats "$TMP/scan.json" -q || fail "scanout of 3 frames (timed)"
[ "$(field "$TMP/scan.json" "len(j['display_periods']) > 4 and j['decoded_equals_frames']")" = True ] && pass \
  || fail "scanout timed: $(field "$TMP/scan.json" "[p['frame'] for p in j['display_periods']]")"
"$BIN" scanout --config "$CFG" --scene "$RGB" -o "$TMP/untimed_%02d.ppm" --stats "$TMP/untimed.json" -q \
  || fail "scanout of 3 frames (untimed)"
[ "$(field "$TMP/untimed.json" "[p['frame'] for p in j['display_periods']]")" = "[0, 1, 2]" ] && pass \
  || fail "scanout untimed periods: $(field "$TMP/untimed.json" "[p['frame'] for p in j['display_periods']]")"
cat > "$TMP/ppm_check.py" <<'PYEOF'
import json, sys
j = json.load(open(sys.argv[1]))
colour = {0: (255, 0, 0), 1: (0, 255, 0), 2: (0, 0, 255)}
shown = [p["frame"] for p in j["display_periods"]]
assert shown == sorted(shown) and [k for k in shown if k >= 0][-1] == 2, shown
assert [k for i, k in enumerate(shown) if k >= 0 and (i == 0 or shown[i - 1] != k)] == [0, 1, 2], shown
for n, k in enumerate(shown):
    data = open(sys.argv[2] % n, "rb").read()
    parts = data.split(b"\n", 3)  # P6, W H, 255, pixels
    px = parts[3]
    cols = {px[i:i + 3] for i in range(0, len(px), 3)}
    assert len(cols) == 1, f"period {n}: {len(cols)} colours (a torn or half-drawn frame)"
    if k >= 0:
        assert tuple(next(iter(cols))) == colour[k], (n, k, next(iter(cols)))
print("ok", shown)
PYEOF
for run in scan untimed; do
  out=$(/usr/bin/python3 "$TMP/ppm_check.py" "$TMP/$run.json" "$TMP/${run}_%02d.ppm" 2>&1) && pass \
    || fail "scanout $run periods: $out"
done

# 9. Errors.
expect_error "range past the end" "frame 7 does not exist: the scene has 6 frames" -- \
  "$BIN" render --config "$CFG" --scene "$SEQ" --frames 7: -q
expect_error "empty range" "is empty" -- "$BIN" render --config "$CFG" --scene "$SEQ" --frames 3:2 -q
expect_error "bad range" "is not A:B" -- "$BIN" simulate --config "$CFG" --scene "$SEQ" --frames x -q
expect_error "bad pattern" "one integer conversion" -- "$BIN" render --config "$CFG" --scene "$SEQ" -o "$TMP/a_%s.png" -q
expect_error "frame-sample range" "must be in \(0, 1\]" -- "$BIN" simulate --config "$CFG" --scene "$SEQ" --frame-sample 0 -q

echo "frames: $passes passed, $fails failed"
[ $fails -eq 0 ]
