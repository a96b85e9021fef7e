#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# End-to-end checks of `rastsim fit` as a user runs it: --help, the format round trip
# through `render --set raster.coord_format=$(rastsim fit ... --format-only)` (same
# framebuffer CRC and fragment stream as the widest format; one fraction bit fewer
# differs), the stats JSON, and clear one-line errors for bad input.
# usage: test_cli_fit.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"
CFG="$SRC/configs/default.toml"

# render_same A B SCENE: the renders with coord formats A and B give the same colour CRC
# and the same fragment trace.
render_same() {
  "$BIN" render --config "$CFG" --scene "$3" --set raster.coord_format="$1" --stats "$TMP/a.json" \
    --fragments "$TMP/a.frag" -q || return 2
  "$BIN" render --config "$CFG" --scene "$3" --set raster.coord_format="$2" --stats "$TMP/b.json" \
    --fragments "$TMP/b.frag" -q || return 2
  [ "$(json_field "$TMP/a.json" framebuffer_crc32)" = "$(json_field "$TMP/b.json" framebuffer_crc32)" ] &&
    cmp -s "$TMP/a.frag" "$TMP/b.frag"
}

# 1. --help documents the options.
"$BIN" fit --help | grep -q -- "--format-only" && pass || fail "fit --help"

# 2. The round trip on every shipped trace: the fit renders as the widest format with the
#    same integer bits, one fraction bit fewer does not.
for t in "$SRC"/traces/*.trace "$SRC"/traces/3d/*.trace; do
  name="$(basename "$t")"
  fmt="$("$BIN" fit --config "$CFG" --scene "$t" --format-only)" || { fail "$name: fit failed"; continue; }
  [[ "$fmt" =~ ^s([0-9]+)\.([0-9]+)$ ]] || { fail "$name: --format-only printed '$fmt'"; continue; }
  I="${BASH_REMATCH[1]}" F="${BASH_REMATCH[2]}"
  render_same "$fmt" "s$I.$((31 - I))" "$t" && pass || fail "$name: $fmt renders differently from s$I.$((31 - I))"
  if [ "$F" -gt 1 ]; then
    render_same "s$I.$((F - 1))" "s$I.$((31 - I))" "$t" && fail "$name: s$I.$((F - 1)) also renders the same" || pass
  else
    "$BIN" fit --config "$CFG" --scene "$t" | grep -q "exact at 0 fraction bits" && pass ||
      fail "$name: F = 1 without saying whether it is exact at 0 fraction bits"
  fi
done

# 3. The summary names the widths and the stats JSON has the fit.
"$BIN" fit --config "$CFG" --scene "$SRC/traces/fill_rule.trace" --stats "$TMP/fit.json" > "$TMP/fit.txt" &&
  grep -q 'raster.coord_format = "s7.3"' "$TMP/fit.txt" && grep -q "edge c/E 23" "$TMP/fit.txt" && pass ||
  fail "fit summary: $(cat "$TMP/fit.txt")"
[ "$(json_field "$TMP/fit.json" coord_format)" = "s7.3" ] && pass || fail "stats coord_format"
"$BIN" fit --config "$CFG" --scene "$SRC/traces/primitives.trace" --precision --stats "$TMP/p.json" > /dev/null
/usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert len(j['precision']) == 17" "$TMP/p.json" &&
  pass || fail "--precision: 17 rows in the stats"

# 4. Bad input: one clear line each, no crash.
expect_error "missing scene" "none.trace" -- "$BIN" fit --scene "$TMP/none.trace"
expect_error "missing config" "nope.toml" -- "$BIN" fit --config "$TMP/nope.toml" --scene "$SRC/traces/state.trace"
printf '[raster]\ncoord_format = \n' > "$TMP/bad.toml"
expect_error "malformed config" "bad.toml:2" -- "$BIN" fit --config "$TMP/bad.toml" --scene "$SRC/traces/state.trace"
printf '[raster]\ncoord_format = "s7"\n' > "$TMP/badfmt.toml"
expect_error "bad format in config" "badfmt.toml:2: raster.coord_format" -- \
  "$BIN" fit --config "$TMP/badfmt.toml" --scene "$SRC/traces/state.trace"
printf 'viewport 128 128\ntri 0 0 10 0 0 zz\n' > "$TMP/bad.trace"
expect_error "malformed trace" "bad.trace:2:" -- "$BIN" fit --scene "$TMP/bad.trace"
printf 'tri 0 0 1e30 0 0 10\n' > "$TMP/huge.trace"
expect_error "vertex beyond every format" "huge.trace:1" -- "$BIN" fit --scene "$TMP/huge.trace"
printf 'tri 0 0 3000000000 0 0 10\n' > "$TMP/far.trace"
expect_error "vertex beyond every format" "far.trace:1: vertex 1 .*fits no coordinate format" -- \
  "$BIN" fit --scene "$TMP/far.trace"

echo "cli fit: $passes passed, $fails failed"
[ $fails -eq 0 ]
