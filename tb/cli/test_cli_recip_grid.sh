#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# End-to-end checks of `rastsim recip-grid` (docs/clip-space.md, "Where methods fail"):
# the CSV's shape, its exact settings against `rastsim fit`'s (which compares the render
# signature, framebuffer and fragment-stream CRCs, not values), the summary on stderr
# with --output -, and clear errors for bad input.
# usage: test_cli_recip_grid.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"
CFG="$SRC/configs/default.toml"
CUBE="$SRC/traces/3d/clip_cube.trace"

# 1. --help documents the options.
"$BIN" recip-grid --help | grep -q -- "--output" && pass || fail "recip-grid --help"

# 2. The CSV: a header and 16 x 5 rows, seed bits 1..16 within iterations 0..4.
"$BIN" recip-grid --config "$CFG" --scene "$CUBE" --output "$TMP/g.csv" -q || fail "recip-grid on clip_cube"
[ "$(wc -l < "$TMP/g.csv")" = 81 ] && pass || fail "recip-grid: $(wc -l < "$TMP/g.csv") lines, not 81"
head -1 "$TMP/g.csv" | grep -q "^scene,seed_bits,iterations,fragments,colour_values,.*,texcoord_max_lsb,texcoord_mean_lsb,exact$" &&
  pass || fail "recip-grid: header $(head -1 "$TMP/g.csv")"

# 3. For each step count, the fewest seed bits exact in the CSV are rastsim fit's.
"$BIN" fit --config "$CFG" --scene "$CUBE" --stats "$TMP/fit.json" -q || fail "fit on clip_cube"
/usr/bin/python3 - "$TMP/g.csv" "$TMP/fit.json" <<'PY' && pass || fail "recip-grid's exact settings differ from fit's"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
fit = json.load(open(sys.argv[2]))["perspective"]["fewest_seed_bits_by_iterations"]
for it in range(5):
    exact = [int(r["seed_bits"]) for r in rows if int(r["iterations"]) == it and r["exact"] == "1"]
    if (min(exact) if exact else 0) != fit[str(it)]:
        sys.exit("iterations %d: csv %s, fit %s" % (it, exact[:1], fit[str(it)]))
PY

# 4. --output -: only CSV on stdout, the summary on stderr.
"$BIN" recip-grid --config "$CFG" --scene "$CUBE" >"$TMP/out.csv" 2>"$TMP/err.txt" || fail "recip-grid to stdout"
[ "$(wc -l < "$TMP/out.csv")" = 81 ] && grep -q "^recip-grid: " "$TMP/err.txt" && pass ||
  fail "recip-grid --output -: CSV and summary mixed"

# 5. Bad input: one clear line each.
expect_error "missing scene" "none.trace" -- "$BIN" recip-grid --scene "$TMP/none.trace"
expect_error "unwritable output" "nodir" -- "$BIN" recip-grid --scene "$CUBE" --output "$TMP/nodir/g.csv"

echo "cli recip-grid: $passes passed, $fails failed"
[ $fails -eq 0 ]
