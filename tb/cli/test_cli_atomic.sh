#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Failed and interrupted runs leave nothing behind (docs/exploration.md, "Outputs and
# interruptions"):
#   1. render and simulate on a scene that fails late (a bad last line after 6000
#      triangles, when the fragment stream, VCD and the rest are already being written;
#      a vertex outside the coordinate format, which the model's setup rejects; a
#      viewport larger than the framebuffer): no file at any output path, nothing beside
#      them, and an output file already there keeps its content;
#   2. simulate stopped by SIGINT mid-run: no output and no temporary left;
#   3. a local sweep (two jobs) stopped by SIGINT: the finished rows stay in the CSV, no
#      point's process runs on, the temporary folder is gone, the message gives the
#      --resume command line, and the exit status is 130.
# usage: test_cli_atomic.sh RASTSIM_BINARY SOURCE_DIR
BIN="$1"
SRC="$2"
source "$(dirname "$0")/cli_checks.sh"
export SC_COPYRIGHT_MESSAGE=DISABLE

# A trace of `n` small Gouraud triangles, then the line `last` (nothing when empty).
make_trace() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import random, sys
path, n, last = sys.argv[1], int(sys.argv[2]), sys.argv[3]
r = random.Random(1)
with open(path, "w") as f:
    f.write("viewport 128 128\nclear 0 0 0\n")
    for _ in range(n):
        x, y = r.uniform(0, 120), r.uniform(0, 120)
        f.write(f"tri {x:.2f} {y:.2f} 0.5 200 10 10 {x + 6:.2f} {y:.2f} 0.5 10 200 10 {x:.2f} {y + 6:.2f} 0.5 10 10 200\n")
    if last:
        f.write(last + "\n")
PY
}

# The files in folder $1, one a line (hidden ones too).
listing() { (cd "$1" && ls -A | sort); }

# 1. Late failures: every output path of render and simulate.
make_trace "$TMP/bad_line.trace" 6000 "tri 0 0 10 0 0 zz"
make_trace "$TMP/bad_vertex.trace" 6000 "tri 0 0 500 0 0 10"
make_trace "$TMP/bad_viewport.trace" 6000 "viewport 4096 4096"$'\n'"tri 0 0 10 0 0 10"
for scene in bad_line bad_vertex bad_viewport; do
  for cmd in render simulate; do
    out="$TMP/out-$cmd-$scene"
    mkdir -p "$out"
    args=(-o "$out/image.png" --stats "$out/stats.json" --fragments "$out/fragments.txt")
    [ $cmd = simulate ] && args+=(--vcd "$out/waves.vcd" --timeline "$out/timeline.json" --heatmap "$out/heat.png"
                                  --heatmap-data "$out/heat.json")
    expect_error "$cmd $scene.trace" "$scene.trace:600[34]:" -- "$BIN" $cmd --scene "$TMP/$scene.trace" "${args[@]}"
    left="$(listing "$out")"
    [ -z "$left" ] && pass || fail "$cmd on $scene.trace left files behind: $(tr '\n' ' ' <<<"$left")"
  done
done
# An output already there is left as it was (the same run, every target existing).
out="$TMP/existing"
mkdir -p "$out"
targets=(image.png stats.json fragments.txt waves.vcd timeline.json heat.png heat.json)
for f in "${targets[@]}"; do echo "previous $f" > "$out/$f"; done
expect_error "simulate over existing outputs" "bad_line.trace:6003:" -- "$BIN" simulate --scene "$TMP/bad_line.trace" \
  -o "$out/image.png" --stats "$out/stats.json" --fragments "$out/fragments.txt" --vcd "$out/waves.vcd" \
  --timeline "$out/timeline.json" --heatmap "$out/heat.png" --heatmap-data "$out/heat.json"
for f in "${targets[@]}"; do
  [ "$(cat "$out/$f")" = "previous $f" ] && pass || fail "the failed run changed the existing $f"
done
[ "$(listing "$out" | wc -l)" = ${#targets[@]} ] && pass || fail "temporaries left beside existing outputs: $(listing "$out" | tr '\n' ' ')"
# The same outputs of a run that succeeds all appear (and nothing else).
make_trace "$TMP/good.trace" 200 ""
"$BIN" simulate --scene "$TMP/good.trace" -q -o "$out/image.png" --stats "$out/stats.json" \
  --fragments "$out/fragments.txt" --vcd "$out/waves.vcd" --timeline "$out/timeline.json" --heatmap "$out/heat.png" \
  --heatmap-data "$out/heat.json" && pass || fail "simulate of a good trace failed"
for f in "${targets[@]}"; do
  ! grep -aq "^previous " "$out/$f" && [ -s "$out/$f" ] && pass || fail "the successful run did not write $f"
done
[ "$(listing "$out" | wc -l)" = ${#targets[@]} ] && pass || fail "a successful run left temporaries: $(listing "$out" | tr '\n' ' ')"

# Job control: background jobs get SIGINT as a terminal's Ctrl-C would deliver it (a
# non-interactive shell otherwise starts them with SIGINT ignored).
set -m

# 2. simulate interrupted mid-run: no output, no temporary.
marker="slow-$$-$RANDOM"
/usr/bin/python3 - "$TMP/$marker.trace" <<'PY'
import random, sys
r = random.Random(2)
with open(sys.argv[1], "w") as f:
    f.write("viewport 128 128\nclear 0 0 0\n")
    for _ in range(40000):
        v = [f"{r.uniform(0, 128):.2f} {r.uniform(0, 128):.2f} 0.5 {r.randrange(256)} 9 9" for _ in range(3)]
        f.write("tri " + " ".join(v) + "\n")
PY
out="$TMP/interrupted"
mkdir -p "$out"
"$BIN" simulate --scene "$TMP/$marker.trace" -o "$out/image.png" --stats "$out/stats.json" \
  --fragments "$out/fragments.txt" --vcd "$out/waves.vcd" --timeline "$out/timeline.json" 2>"$TMP/sim.err" &
pid=$!
for _ in $(seq 100); do [ -n "$(listing "$out")" ] && break; sleep 0.1; done
[ -n "$(listing "$out")" ] && pass || fail "simulate wrote nothing within 10 s (the test needs it to be writing)"
kill -INT $pid
wait $pid
rc=$?
[ $rc = 130 ] && pass || fail "interrupted simulate: exit status $rc, expected 130 (SIGINT)"
left="$(listing "$out")"
[ -z "$left" ] && pass || fail "interrupted simulate left files: $(tr '\n' ' ' <<<"$left")"

# 3. A local sweep interrupted: two fast points finish, then two slow ones run (-j 2).
cp "$SRC/traces/state.trace" "$TMP/fast.trace"
"$BIN" sweep --scene "$TMP/fast.trace" --scene "$TMP/$marker.trace" --set raster.tile_size=8,16 -j 2 \
  --out "$TMP/sweep.csv" 2>"$TMP/sweep.err" &
pid=$!
running=""
for _ in $(seq 300); do
  rows=$( [ -f "$TMP/sweep.csv" ] && tail -n +2 "$TMP/sweep.csv" | grep -c . )
  running="$(pgrep -f -- "simulate .*$marker")"  # a point, not the sweep itself
  [ "${rows:-0}" -ge 2 ] && [ -n "$running" ] && break
  sleep 0.1
done
[ -n "$running" ] && pass || fail "the sweep's slow points never started"
sleep 0.5
kill -INT $pid
wait $pid
rc=$?
[ $rc = 130 ] && pass || fail "interrupted sweep: exit status $rc, expected 130 (SIGINT): $(tail -3 "$TMP/sweep.err")"
for _ in $(seq 20); do [ -z "$(pgrep -f -- "$marker")" ] && break; sleep 0.1; done
still="$(pgrep -f -- "$marker")"
[ -z "$still" ] && pass || { fail "processes of the interrupted sweep run on: $still"; kill $still 2>/dev/null; }
tmpdirs="$(ls -d "${TMPDIR:-/tmp}"/rastsim-sweep-$pid* 2>/dev/null)"
[ -z "$tmpdirs" ] && pass || { fail "the sweep's temporary folder is left: $tmpdirs"; rm -rf $tmpdirs; }
/usr/bin/python3 - "$TMP/sweep.csv" "$TMP/fast.trace" <<'PY' && pass || fail "the finished rows were not kept"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
assert all(r["scene"] == sys.argv[2] and r["status"] == "ok" for r in rows), rows
assert sorted(r["raster.tile_size"] for r in rows) == ["16", "8"], rows
PY
grep -q "2 of 4 rows finished and kept in $TMP/sweep.csv" "$TMP/sweep.err" && pass ||
  fail "the message does not say what was kept: $(cat "$TMP/sweep.err")"
grep -q -- "--out $TMP/sweep.csv --resume\$" "$TMP/sweep.err" && pass ||
  fail "the message gives no --resume command line: $(cat "$TMP/sweep.err")"

echo "cli.atomic: $passes passed, $fails failed"
[ $fails -eq 0 ]
