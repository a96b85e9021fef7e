#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Any config through the RTL (docs/rtl.md, "Any config through the RTL"): a config no
# shipped model fits (the embedded config with a 3-entry tile FIFO) is built once into
# the RTL cache and co-simulated; ctest label rtlbuild (one on-demand build, ~1 minute).
#   1. two `rastsim cosim` at once on a cold cache: both pass (0 mismatches, SystemC
#      within the 5 % the shipped cosim tests allow), one builds, the other waits for the
#      lock and finds the entry: one entry in the cache, its header the config's export;
#   2. a third run is a cache hit: nothing rebuilt (the runner file untouched);
#   3. `rastsim sweep --level cosim` over two cull modes (run-time inputs, same model):
#      cycles_rtl, mismatches, cycle_error beside the SystemC columns, no build;
#   4. the shipped config itself still runs on its shipped model;
#   5. `rastsim rtl-cache` lists the entry, `--clean` removes it.
# usage: test_rtl_cache.sh RASTSIM_BINARY SOURCE_DIR CACHE_DIR
BIN="$1"
SRC="$2"
CACHE="$3"
source "$SRC/tb/cli/cli_checks.sh"
export RASTSIM_CACHE="$CACHE" SC_COPYRIGHT_MESSAGE=DISABLE
SCENE="$SRC/traces/primitives.trace"
CFG=(--config "$SRC/configs/embedded.toml" --set fifo.tile_depth=3)
rm -rf "$CACHE/rtl"  # cold: the lock test needs a build

# 0. A cache that cannot be written: the error names the config (no build starts).
expect_error "unwritable cache" "embedded.toml --set fifo.tile_depth=3: no RTL model for this config: .*cannot create" -- \
  env RASTSIM_CACHE=/proc/rastsim-no-such-dir "$BIN" cosim "${CFG[@]}" --scene "$SCENE"

# 1. Two processes, one build.
"$BIN" cosim "${CFG[@]}" --scene "$SCENE" --max-error 0.05 --stats "$TMP/a.json" >"$TMP/a.out" 2>"$TMP/a.err" &
pa=$!
"$BIN" cosim "${CFG[@]}" --scene "$SCENE" --max-error 0.05 --stats "$TMP/b.json" >"$TMP/b.out" 2>"$TMP/b.err" &
pb=$!
wait $pa && pass || fail "first cosim failed: $(tail -3 "$TMP/a.err")"
wait $pb && pass || fail "second cosim failed: $(tail -3 "$TMP/b.err")"
builds=$(cat "$TMP/a.err" "$TMP/b.err" | grep -c "rastsim: building RTL model")
waits=$(cat "$TMP/a.err" "$TMP/b.err" | grep -c "waiting for another process building RTL model")
[ "$builds" = 1 ] && pass || fail "expected one build, saw $builds"
[ "$waits" = 1 ] && pass || fail "expected one process waiting for the lock, saw $waits"
entries=$(find "$CACHE/rtl" -mindepth 1 -maxdepth 1 -type d -regextype egrep -regex '.*/[0-9a-f]{16}' | wc -l)
[ "$entries" = 1 ] && pass || fail "expected one cache entry, found $entries: $(ls "$CACHE/rtl")"
hits=""
for r in a b; do
  [ "$(json_field "$TMP/$r.json" mismatches)" = 0 ] && pass || fail "$r: mismatches $(json_field "$TMP/$r.json" mismatches)"
  [[ "$(json_field "$TMP/$r.json" rtl_model)" == cache:* ]] && pass || fail "$r: rtl_model is not on demand"
  [ "$(json_field "$TMP/$r.json" framebuffer_crc32_rtl)" = "$(json_field "$TMP/$r.json" framebuffer_crc32_ref)" ] &&
    pass || fail "$r: framebuffer CRC differs from the reference"
  hits="$hits$(json_field "$TMP/$r.json" rtl_cache_hit)"
done
[[ "$hits" == "TrueFalse" || "$hits" == "FalseTrue" ]] && pass || fail "rtl_cache_hit of the two runs: $hits"
[ "$(json_field "$TMP/a.json" cycles_rtl)" = "$(json_field "$TMP/b.json" cycles_rtl)" ] && pass ||
  fail "the two runs' cycles_rtl differ"
# The entry was built with the config's parameters: its header is `export-rtl`'s (banners aside).
entry="$(json_field "$TMP/a.json" rtl_model_dir)"
"$BIN" export-rtl "${CFG[@]}" -o "$TMP/export.vh" && pass || fail "export-rtl failed"
if diff <(grep parameter "$TMP/export.vh") <(grep parameter "$entry/rast_params.vh") >/dev/null; then pass
else fail "the entry's rast_params.vh is not export-rtl's"; fi
grep -q "TileFifoDepth = 3" "$entry/rast_params.vh" && pass || fail "the entry lacks TileFifoDepth = 3"

# 2. A cache hit rebuilds nothing.
before=$(stat -c %Y.%N "$entry/rast_runner")
"$BIN" cosim "${CFG[@]}" --scene "$SCENE" --max-error 0.05 --stats "$TMP/c.json" >"$TMP/c.out" 2>"$TMP/c.err" &&
  pass || fail "third cosim failed: $(tail -3 "$TMP/c.err")"
grep -q "(cache hit)" "$TMP/c.out" && pass || fail "third run does not report a cache hit: $(cat "$TMP/c.out")"
[ "$(json_field "$TMP/c.json" rtl_cache_hit)" = True ] && pass || fail "third run: rtl_cache_hit not true"
grep -q "building" "$TMP/c.err" && fail "third run built: $(cat "$TMP/c.err")" || pass
[ "$(stat -c %Y.%N "$entry/rast_runner")" = "$before" ] && pass || fail "the runner was rebuilt"
"$BIN" cosim "${CFG[@]}" --rtl-build-only >"$TMP/d.out" 2>&1 && grep -q "in the cache: $entry" "$TMP/d.out" &&
  pass || fail "--rtl-build-only: $(cat "$TMP/d.out")"

# 3. The sweep through the RTL: a row a cull mode, the RTL's columns beside SystemC's.
if "$BIN" sweep "${CFG[@]}" --set raster.cull=none,back --scene "$SCENE" --level cosim --jobs 2 \
     --out "$TMP/s.csv" 2>"$TMP/s.err"; then
  pass
  grep -q "building" "$TMP/s.err" && fail "the sweep built a model: $(cat "$TMP/s.err")" || pass
  /usr/bin/python3 - "$TMP/s.csv" "$(json_field "$TMP/a.json" cycles_rtl)" <<'PY' && pass || fail "sweep CSV"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
for r in rows:
    for k in ("cycles", "stages.rop.busy", "cycles_rtl", "mismatches", "cycle_error", "rtl_model"):
        assert r.get(k, "") != "", (k, r)
    assert r["status"] == "ok" and r["mismatches"] == "0", r
    assert r["rtl_model"].startswith("cache:"), r
    c, rtl = int(r["cycles"]), int(r["cycles_rtl"])
    assert abs(float(r["cycle_error"]) - (c - rtl) / rtl) < 1e-9, r
    assert abs(c - rtl) <= 0.05 * rtl, r
# cull = none is the embedded config's own: the same run as step 1.
none = [r for r in rows if r["raster.cull"] == "none"][0]
assert none["cycles_rtl"] == sys.argv[2], (none["cycles_rtl"], sys.argv[2])
PY
else
  fail "sweep --level cosim failed: $(tail -3 "$TMP/s.err")"
fi

# 4. The shipped config runs on its shipped model, without the cache.
"$BIN" cosim --config "$SRC/configs/embedded.toml" --scene "$SCENE" --no-model --stats "$TMP/e.json" >/dev/null 2>&1 &&
  [ "$(json_field "$TMP/e.json" rtl_model)" = embedded ] && pass || fail "the shipped embedded model did not run"

# 5. rtl-cache lists the entry, --clean removes it (and its lock).
key="$(basename "$entry")"
"$BIN" rtl-cache >"$TMP/l.out" 2>&1 && grep -q "^$key .*fifo.tile_depth=3" "$TMP/l.out" && pass ||
  fail "rtl-cache does not list $key: $(cat "$TMP/l.out")"
"$BIN" rtl-cache --clean >"$TMP/l.out" 2>&1 && grep -q "removed 1 entries" "$TMP/l.out" && [ ! -e "$entry" ] &&
  [ ! -e "$CACHE/rtl/$key.lock" ] && pass || fail "rtl-cache --clean: $(cat "$TMP/l.out")"

echo "rtl cache checks: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
