#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What a script reads from `rastsim`: `--stats -` puts only JSON on stdout (the summary
# goes to stderr), -q/--quiet silences every command, the flags are spelled alike on
# every command, `--sample 0` is refused, and the summary line names every triangle
# that was not drawn and why (docs/stats.md).
# usage: test_cli_stdout.sh RASTSIM_BINARY SOURCE_DIR [area]
#   area: only `rastsim area` (Yosys; ctest -L area), else every other command.
BIN="$1"
SRC="$2"
MODE="${3:-}"
source "$(dirname "$0")/cli_checks.sh"
export SC_COPYRIGHT_MESSAGE=DISABLE

SCENE="$SRC/traces/torus.trace"
EMB="$SRC/configs/embedded.toml"

# is_json NAME FILE: the whole file parses as one JSON object.
is_json() {
  /usr/bin/python3 -c "import json,sys; j=json.loads(open(sys.argv[1]).read()); assert isinstance(j, dict)" "$2" \
    2>/dev/null && pass || fail "$1: stdout is not only JSON: $(head -c 300 "$2")"
}

# stats_stdout NAME ARGS...: `rastsim ARGS --stats -` exits 0 and its stdout parses as JSON.
stats_stdout() {
  local name="$1"; shift
  if "$BIN" "$@" --stats - >"$TMP/out.json" 2>"$TMP/err.txt"; then
    is_json "$name --stats -" "$TMP/out.json"
  else
    fail "$name --stats - failed: $(tail -n 3 "$TMP/err.txt")"
  fi
}

# quiet NAME ARGS...: `rastsim ARGS -q` exits 0 and prints nothing on stdout or stderr.
quiet() {
  local name="$1"; shift
  if "$BIN" "$@" -q >"$TMP/q.out" 2>"$TMP/q.err"; then
    [ ! -s "$TMP/q.out" ] && [ ! -s "$TMP/q.err" ] && pass ||
      fail "$name -q printed: $(head -c 300 "$TMP/q.out") $(head -c 300 "$TMP/q.err")"
  else
    fail "$name -q failed: $(tail -n 3 "$TMP/q.err")"
  fi
}

if [ "$MODE" = area ]; then
  # The fine raster of a 16 x 16 display with s4.2 coordinates and 4 px tiles (as
  # tb/area/test_area.cpp's small_config): a few seconds of Yosys the first time, then
  # cached (the embedded config's took a minute on every fresh machine).
  AREA=(area --config "$EMB" --set display.width=16 --set display.height=16 --set raster.coord_format=s4.2
        --set raster.tile_size=4 --set fine.samples_per_cycle=1 --set raster.max_samples=2 --top rast_fine_raster)
  stats_stdout area "${AREA[@]}"
  grep -q "^area: " "$TMP/err.txt" && pass || fail "area: the summary did not go to stderr"
  quiet area "${AREA[@]}" --stats "$TMP/area.json"
  is_json "area -q --stats FILE" "$TMP/area.json"
  echo "cli stdout (area): $passes passed, $fails failed"
  [ $fails -eq 0 ]
  exit
fi

# 1. Every command that has --stats is covered below (a new one must be added here).
commands="$("$BIN" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF {print $1}')"
[ -n "$commands" ] && pass || fail "no subcommands in rastsim --help"
for c in $commands; do
  "$BIN" $c --help | grep -q -- "--stats" || continue
  case $c in
    render|simulate|estimate|cosim|fit|scanout|monitor|coverage-error|area|dram-replay) pass ;;
    *) fail "$c has --stats but no check in test_cli_stdout.sh" ;;
  esac
done

# 2. --stats -: only JSON on stdout, for every mode that prints a summary.
"$BIN" scanout --config "$EMB" --scene "$SCENE" -o "$TMP/so.png" --signal "$TMP/sig.vcd" --signal-frames 2 -q ||
  fail "scanout --signal for the monitor checks"
stats_stdout render render --scene "$SCENE"
grep -q "^render: " "$TMP/err.txt" && pass || fail "render: the summary did not go to stderr"
stats_stdout simulate simulate --scene "$SCENE"
grep -q "^simulate: " "$TMP/err.txt" && pass || fail "simulate: the summary did not go to stderr"
stats_stdout "simulate --sample" simulate --scene "$SCENE" --sample 0.5
stats_stdout "simulate --tolerance" simulate --scene "$SCENE" --tolerance 50%
stats_stdout estimate estimate --scene "$SCENE"
stats_stdout fit fit --scene "$SRC/traces/primitives.trace"
stats_stdout "fit --precision" fit --scene "$SRC/traces/primitives.trace" --precision
stats_stdout scanout scanout --config "$EMB" --scene "$SCENE" -o "$TMP/so.png"
stats_stdout "scanout --timed" scanout --config "$EMB" --scene "$SCENE" -o "$TMP/so.png" --timed
stats_stdout monitor monitor --config "$EMB" --signal "$TMP/sig.vcd" -o "$TMP/mon.png"
stats_stdout coverage-error coverage-error --scene "$SRC/traces/aa/thin.trace" --samples 1,4
stats_stdout dram-replay dram-replay "$SRC/tb/timing/data/stream4.memtrace"
grep -q "^dram-replay: " "$TMP/err.txt" && pass || fail "dram-replay: the summary did not go to stderr"
stats_stdout cosim cosim --config "$EMB" --scene "$SRC/traces/primitives.trace"
grep -q "^cosim: " "$TMP/err.txt" && pass || fail "cosim: the summary did not go to stderr"
stats_stdout "cosim --no-model" cosim --config "$EMB" --scene "$SRC/traces/primitives.trace" --no-model
stats_stdout "cosim --trace-diff" cosim --config "$EMB" --scene "$SRC/traces/primitives.trace" --trace-diff "$TMP/td"
stats_stdout "cosim --simulate-stats" cosim --config "$EMB" --scene "$SRC/traces/primitives.trace" --simulate-stats
# Two outputs cannot share stdout: refused before the run.
expect_error "two outputs on stdout" "stdout" -- "$BIN" simulate --scene "$SCENE" --stats - --heatmap-data -
expect_error "fit --format-only with --stats -" "stdout" -- "$BIN" fit --scene "$SCENE" --format-only --stats -

# 3. -q/--quiet on every command: nothing on stdout or stderr when all goes well.
for c in $commands; do
  "$BIN" $c --help | grep -Eq -- "-q, *--quiet|--quiet, *-q" && pass || fail "$c --help lacks -q/--quiet"
done
quiet config config --config "$EMB"
quiet render render --scene "$SCENE" -o "$TMP/q.png" --stats "$TMP/q.json"
quiet simulate simulate --scene "$SCENE" --stats "$TMP/q.json"
quiet "simulate --sample" simulate --scene "$SCENE" --sample 0.5 --stats "$TMP/q.json"
quiet estimate estimate --scene "$SCENE"
quiet fit fit --scene "$SRC/traces/primitives.trace" --precision --stats "$TMP/q.json"
is_json "fit -q --stats FILE" "$TMP/q.json"
quiet scanout scanout --config "$EMB" --scene "$SCENE" -o "$TMP/so.png"
quiet monitor monitor --config "$EMB" --signal "$TMP/sig.vcd" -o "$TMP/mon.png"
quiet coverage-error coverage-error --scene "$SRC/traces/aa/thin.trace" --samples 1,4
quiet dram-replay dram-replay "$SRC/tb/timing/data/stream4.memtrace" --stats "$TMP/q.json"
is_json "dram-replay -q --stats FILE" "$TMP/q.json"
quiet cosim cosim --config "$EMB" --scene "$SRC/traces/primitives.trace" --stats "$TMP/q.json"
is_json "cosim -q --stats FILE" "$TMP/q.json"
quiet "cosim --rtl-build-only" cosim --config "$EMB" --rtl-build-only
quiet export-rtl export-rtl --config "$EMB" -o "$TMP/q.vh"
quiet export-rtl-scanout export-rtl-scanout --config "$EMB" -o "$TMP/q_so.vh"
quiet rtl-cache rtl-cache
quiet sweep sweep --scene "$SRC/traces/state.trace" --set raster.tile_size=8,16 -j1 --output "$TMP/q.csv"
[ "$(wc -l < "$TMP/q.csv")" = 3 ] && pass || fail "sweep -q wrote $(wc -l < "$TMP/q.csv") lines, expected 3"

# 4. One spelling: -o/--output (sweep's old --out still read), --threads for threads and
#    -j/--jobs for processes (each says so), --seed for every random choice.
for c in render simulate scanout monitor export-rtl export-rtl-scanout sweep; do
  "$BIN" $c --help | grep -Eq -- "-o, *--output" && pass || fail "$c --help lacks -o, --output"
done
"$BIN" sweep --help | grep -q -- "--out " && fail "sweep --help still shows --out" || pass
"$BIN" sweep --scene "$SRC/traces/state.trace" --set raster.tile_size=8,16 -j1 -q -o "$TMP/o1.csv" &&
  "$BIN" sweep --scene "$SRC/traces/state.trace" --set raster.tile_size=8,16 -j1 -q --out "$TMP/o2.csv" &&
  [ "$(cut -d, -f1-4 "$TMP/o1.csv")" = "$(cut -d, -f1-4 "$TMP/o2.csv")" ] && pass || fail "sweep -o / --out"
expect_error "sweep without --output" "--output" -- "$BIN" sweep --scene "$SRC/traces/state.trace"
"$BIN" render --help | grep -A3 -- "--threads" | grep -qi "thread" && pass || fail "render --threads help"
for c in sweep area; do
  "$BIN" $c --help | grep -E -A2 -- "-j, *--jobs" | grep -qi "process" && pass || fail "$c -j/--jobs help says processes"
done
for c in simulate cosim; do
  "$BIN" $c --help | grep -q -- "--seed " && pass || fail "$c --help lacks --seed"
  "$BIN" $c --help | grep -Eq -- "--(stall|sample|stress)-seed" && fail "$c --help shows an old seed name" || pass
done
# One seed: --seed and the old --sample-seed give the same sampled run; another seed another.
s() { "$BIN" simulate --scene "$SCENE" --sample 0.3 -q --stats - "$@" | /usr/bin/python3 -c \
        "import json,sys; j=json.load(sys.stdin); print(j['cycles'], j['sample_seed'])"; }
a="$(s --seed 5)"; b="$(s --sample-seed 5)"; c="$(s --seed 6)"
[ -n "$a" ] && [ "$a" = "$b" ] && [ "${a#* }" = 5 ] && [ "${c#* }" = 6 ] && pass || fail "--seed: '$a' '$b' '$c'"

# 5. --sample 0 is an error (0 < F <= 1), as are other values outside; 1 is allowed.
expect_error "--sample 0" "--sample.*\(0, 1\]" -- "$BIN" simulate --scene "$SCENE" --sample 0
expect_error "--sample -0.5" "--sample" -- "$BIN" simulate --scene "$SCENE" --sample -0.5
expect_error "--sample 1.5" "--sample" -- "$BIN" simulate --scene "$SCENE" --sample 1.5
"$BIN" simulate --scene "$SCENE" --sample 1 -q && pass || fail "--sample 1 refused"

# 6. The summary names every triangle not drawn, by reason. By construction (y down,
#    front_face ccw, cull back, out_of_range cull, s7.16 holds x in [-128, 128)): 3 drawn,
#    2 back faces, 1 zero area, 1 vertex at x = 500, 2 outside the scissor box.
cat > "$TMP/reasons.trace" <<'EOF'
viewport 128 128
tri 0 0 0 10 10 0
tri 20 20 20 30 30 20
tri 0 0 10 0 0 10
tri 40 40 50 40 40 50
tri 0 0 5 5 10 10
tri 0 0 0 10 500 0
scissor 0 0 16 16
tri 60 60 60 70 70 60
tri 100 100 100 110 110 100
tri 2 2 2 12 12 2
EOF
want="9 triangles (6 not drawn: 2 culled by facing, 1 zero area, 1 out of range, 2 outside the clip)"
R=(--scene "$TMP/reasons.trace" --set raster.cull=back --set raster.out_of_range=cull)
for c in render simulate estimate; do
  line="$("$BIN" $c "${R[@]}" --stats "$TMP/r.json")"
  grep -qF "$want" <<<"$line" && pass || fail "$c summary: '$line', expected '$want'"
  [ "$(json_field "$TMP/r.json" triangles_rasterized)" = 3 ] && pass || fail "$c: triangles_rasterized != 3"
done
line="$("$BIN" render --scene "$SRC/traces/primitives.trace" --stats "$TMP/r.json")"
n="$(json_field "$TMP/r.json" triangles_in)"
grep -qF "$n triangles (all drawn)" <<<"$line" && pass || fail "render summary with every triangle drawn: '$line'"

echo "cli stdout: $passes passed, $fails failed"
[ $fails -eq 0 ]
