#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Multi-frame traces end to end (docs/trace-format.md "Frames"): -o out_%04d.png, frames[],
# --frames A:B against the full run (images byte for byte, simulate's cycles for 0:N, the
# estimate's per-frame work), the range and pattern errors, --frame-sample 1 = the full run.
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

# 6. Errors.
expect_error "range past the end" "frame 7 does not exist: the scene has 6 frames" -- \
  "$BIN" render --config "$CFG" --scene "$SEQ" --frames 7: -q
expect_error "empty range" "is empty" -- "$BIN" render --config "$CFG" --scene "$SEQ" --frames 3:2 -q
expect_error "bad range" "is not A:B" -- "$BIN" simulate --config "$CFG" --scene "$SEQ" --frames x -q
expect_error "bad pattern" "one integer conversion" -- "$BIN" render --config "$CFG" --scene "$SEQ" -o "$TMP/a_%s.png" -q
expect_error "frame-sample range" "must be in \(0, 1\]" -- "$BIN" simulate --config "$CFG" --scene "$SEQ" --frame-sample 0 -q

echo "frames: $passes passed, $fails failed"
[ $fails -eq 0 ]
