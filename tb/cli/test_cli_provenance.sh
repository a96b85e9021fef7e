#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What produced an output, as a user scripts it: `config --toml` read back gives the same
# config for every shipped config; each stats JSON's provenance (version, command line,
# config file, --set in order, canonical config and its hash, scene and the hash of its
# bytes) with the hashes recomputed here (FNV-1a 64 in Python); `config --from-stats`
# reproduces a run; the sweep CSV's fixed --set and rastsim_version columns; --version;
# did-you-mean on a mistyped key.
# usage: test_cli_provenance.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"

SCENE="$SRC/traces/state.trace"
CFG="$SRC/configs/default.toml"
PY=/usr/bin/python3
# FNV-1a 64 of a file's bytes (or of stdin with "-"), 16 hex digits: an independent copy.
cat > "$TMP/fnv.py" <<'PY'
import sys
data = sys.stdin.buffer.read() if sys.argv[1] == "-" else open(sys.argv[1], "rb").read()
h = 0xcbf29ce484222325
for b in data:
    h = ((h ^ b) * 0x100000001b3) & 0xffffffffffffffff
print("%016x" % h)
PY
fnv() { "$PY" "$TMP/fnv.py" "$1"; }
# prov FILE KEY: provenance[KEY] of a stats JSON, lists and null as JSON.
prov() { "$PY" -c "import json,sys; v=json.load(open(sys.argv[1]))['provenance'][sys.argv[2]]; print(v if isinstance(v, str) else json.dumps(v))" "$1" "$2"; }

# 1. config --toml reads back to the same config: every shipped config, alone and with
#    overrides of each type (integer, enum, boolean, number, string); each [section] once.
n=0
for c in "$SRC"/configs/*.toml "$SRC"/configs/*/*.toml; do
  for sets in "" "--set raster.tile_size=8 --set raster.depth_func=less --set raster.depth_write=false" \
              "--set display.width=640 --set display.height=480 --set clock.core_mhz=333.3333333333333" \
              "--set raster.coord_format=s12.4 --set raster.cull=back"; do
    n=$((n + 1))
    # shellcheck disable=SC2086
    if ! "$BIN" config --config "$c" $sets --toml > "$TMP/r$n.toml" 2>"$TMP/r$n.err"; then
      grep -q "not allowed\|does not fit" "$TMP/r$n.err" && continue  # an override this config refuses
      fail "config --toml of $c $sets: $(cat "$TMP/r$n.err")"; continue
    fi
    "$BIN" config --config "$TMP/r$n.toml" --toml > "$TMP/rr$n.toml" 2>"$TMP/rr$n.err" &&
      cmp -s "$TMP/r$n.toml" "$TMP/rr$n.toml" && pass ||
      fail "config --toml of $c $sets does not read back: $(head -c 300 "$TMP/rr$n.err")"
    [ -z "$(grep '^\[' "$TMP/r$n.toml" | sort | uniq -d)" ] && pass || fail "$c: a [section] twice in --toml"
  done
done
[ -z "$("$BIN" config --doc | grep '^\[' | sort | uniq -d)" ] && pass || fail "config --doc: a [section] twice"

# 2. --version: "rastsim <git describe>", the version every stats JSON records.
version="$("$BIN" --version)"
[[ "$version" =~ ^rastsim\ [0-9a-zA-Z._-]+$ ]] && pass || fail "--version printed '$version'"

# 3. simulate --set raster.tile_size=8: the provenance holds the override, the config and
#    its hash (FNV-1a 64 of config_toml, which is `config --toml` of the same options), the
#    scene's hash, the version and the command line; --from-stats reproduces the run.
if "$BIN" simulate --config "$CFG" --scene "$SCENE" --set raster.tile_size=8 --set raster.cull=back \
     --stats "$TMP/s.json" -q; then
  [ "$(prov "$TMP/s.json" sets)" = '["raster.tile_size=8", "raster.cull=back"]' ] && pass || fail "provenance.sets: $(prov "$TMP/s.json" sets)"
  [ "$(prov "$TMP/s.json" config_path)" = "$CFG" ] && pass || fail "provenance.config_path"
  "$BIN" config --config "$CFG" --set raster.tile_size=8 --set raster.cull=back --toml > "$TMP/want.toml"
  prov "$TMP/s.json" config_toml > "$TMP/got.toml"
  cmp -s <(cat "$TMP/want.toml"; echo) "$TMP/got.toml" && pass || fail "provenance.config_toml is not config --toml"
  [ "$(prov "$TMP/s.json" config_hash)" = "$(fnv "$TMP/want.toml")" ] && pass || fail "provenance.config_hash"
  [ "$(prov "$TMP/s.json" scene_path)" = "$SCENE" ] && pass || fail "provenance.scene_path"
  [ "$(prov "$TMP/s.json" scene_hash)" = "$(fnv "$SCENE")" ] && pass || fail "provenance.scene_hash"
  [ "rastsim $(prov "$TMP/s.json" rastsim_version)" = "$version" ] && pass || fail "provenance.rastsim_version"
  prov "$TMP/s.json" argv | grep -q '"simulate", "--config", ".*", "--scene", ".*state.trace", "--set", "raster.tile_size=8"' &&
    pass || fail "provenance.argv: $(prov "$TMP/s.json" argv)"
  "$BIN" config --from-stats "$TMP/s.json" > "$TMP/from.toml" && cmp -s "$TMP/from.toml" "$TMP/want.toml" && pass ||
    fail "config --from-stats is not config --set ... --toml"
  "$BIN" simulate --config "$TMP/from.toml" --scene "$SCENE" --stats "$TMP/s2.json" -q &&
    for k in cycles framebuffer_crc32 fragments; do
      [ "$(json_field "$TMP/s.json" $k)" = "$(json_field "$TMP/s2.json" $k)" ] && pass || fail "rerun from --from-stats: $k differs"
    done
  [ "$(prov "$TMP/s2.json" config_hash)" = "$(prov "$TMP/s.json" config_hash)" ] && pass || fail "rerun: another config hash"
else
  fail "simulate with --stats"
fi
printf '{"cycles": 1}\n' > "$TMP/noprov.json"
expect_error "from-stats without provenance" "noprov.json: no provenance.config_toml" -- "$BIN" config --from-stats "$TMP/noprov.json"
"$PY" -c "import json,sys; j=json.load(open(sys.argv[1])); j['provenance']['config_toml'] += '# edited\n'; json.dump(j, open(sys.argv[2], 'w'))" \
  "$TMP/s.json" "$TMP/edited.json"
expect_error "from-stats of an edited config" "does not match its config_hash" -- "$BIN" config --from-stats "$TMP/edited.json"

# 4. The scene hash is of the bytes as stored: a compressed scene hashes its .gz file.
gzip -c "$SCENE" > "$TMP/state.trace.gz"
"$BIN" render --scene "$TMP/state.trace.gz" --stats "$TMP/gz.json" -q &&
  [ "$(prov "$TMP/gz.json" scene_hash)" = "$(fnv "$TMP/state.trace.gz")" ] && pass || fail "scene_hash of a .gz scene"
[ "$(prov "$TMP/gz.json" config_path)" = "null" ] && [ "$(prov "$TMP/gz.json" sets)" = "[]" ] && pass ||
  fail "a run without --config or --set: config_path null, sets []"

# 5. Every command's stats JSON has the provenance (area: its own test label, Yosys).
P="$SRC/traces/primitives.trace"
for cmd in "render --scene $SCENE" "estimate --scene $SCENE" "fit --scene $SCENE" \
           "coverage-error --scene $SRC/traces/aa/near_horizontal.trace --samples 1,4" \
           "scanout --scene $SCENE -o $TMP/so.png" "cosim --scene $P" "simulate --scene $SCENE --sample 0.5"; do
  name="${cmd%% *}"
  # shellcheck disable=SC2086
  if "$BIN" $cmd --config "$CFG" --set raster.depth_func=less --stats "$TMP/$name.json" >/dev/null 2>"$TMP/$name.err"; then
    [ "$(prov "$TMP/$name.json" sets)" = '["raster.depth_func=less"]' ] &&
      [ "$(prov "$TMP/$name.json" config_hash)" = "$("$BIN" config --config "$CFG" --set raster.depth_func=less --toml | fnv -)" ] &&
      pass || fail "$name: provenance missing or wrong"
  else
    fail "$name --stats: $(tail -n 1 "$TMP/$name.err")"
  fi
done

# 6. The sweep CSV holds each fixed --set (one column, its value on every row) and the
#    version; provenance is not flattened into columns; a resume with other fixed keys
#    is refused, with the same ones it runs nothing.
SW=(sweep --config "$CFG" --scene "$SCENE" --set raster.depth_func=less --set raster.tile_size=8,16 --set raster.cull=back -j1)
if "$BIN" "${SW[@]}" --out "$TMP/sw.csv" 2>/dev/null; then
  "$PY" - "$TMP/sw.csv" "${version#rastsim }" <<'PY' && pass || fail "sweep CSV columns"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
head = next(csv.reader(open(sys.argv[1])))
assert head[:8] == ["scene", "raster.tile_size", "level", "config_hash", "status", "raster.depth_func", "raster.cull",
                    "rastsim_version"], head
assert not [c for c in head if c.startswith("provenance")], head
assert len(rows) == 2 and all(r["raster.depth_func"] == "less" and r["raster.cull"] == "back" for r in rows), rows
assert all(r["rastsim_version"] == sys.argv[2] for r in rows), rows
PY
  "$BIN" "${SW[@]}" --out "$TMP/sw.csv" --resume 2>"$TMP/sw.err" && grep -q "2 of 2 rows already" "$TMP/sw.err" && pass ||
    fail "sweep --resume with the same fixed --set"
  expect_error "resume with another fixed --set" "needs a CSV of this sweep's columns \(.*status, rastsim_version\), it has \(.*status, raster.depth_func" -- \
    "$BIN" sweep --config "$CFG" --scene "$SCENE" --set raster.tile_size=8,16 --out "$TMP/sw.csv" --resume
else
  fail "sweep with fixed --set"
fi

# 7. A mistyped key suggests the key meant; a key like none suggests nothing.
expect_error "did you mean" "unknown key 'raster.tile_sise' \(did you mean 'raster.tile_size'\?\)" -- \
  "$BIN" config --set raster.tile_sise=8
printf '[raster]\ndepht_func = "less"\n' > "$TMP/typo.toml"
expect_error "did you mean in a file" "typo.toml:2: unknown key 'raster.depht_func' \(did you mean 'raster.depth_func'\?\)" -- \
  "$BIN" config --config "$TMP/typo.toml"
expect_error "no suggestion" "unknown key 'raster.xyzzy' \(\`rastsim config --doc\` lists every key\)" -- \
  "$BIN" config --set raster.xyzzy=1

echo "provenance checks: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
