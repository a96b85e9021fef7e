#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest apps.frame_sample_glmark2: frame sampling on a real program's frames (issue 30;
# docs/fidelity.md "Frame sampling", docs/results.md "Frame sampling on the 100-frame
# sequences", where the 100-frame runs are). Captures FRAMES frames of glmark2's SCENE at
# SIZE (scripts/capture_glmark2), imports them (rastsim import-apitrace --config-out), and
# runs `rastsim simulate` on configs/d3d11.toml at that size twice: the full SystemC run,
# and `--frame-sample 0.05`. Checks, against the full run (the independent reference: every
# frame simulated, frames[].cycles summing to its cycles):
#   - the frame-sampled level simulated fewer frames than there are;
#   - its 95 % interval covers the full run's cycles, and its estimate is within 5 %;
#   - each frame it measured (frames_simulated_cycles) is within 10 % of that frame's
#     frames[].cycles in the full run (the scene's last frame left out: it holds the run's end);
#   - both measured each frame at the ROP (frame_boundary "rop": every glmark2 frame starts
#     with its clear), and the full run's frames[].cycles_fetch (at command fetch) sum to
#     its cycles as well;
# and that the same checks refuse a full run of 1.3x the cycles (they can fail).
# glmark2 animates by wall time, so every capture differs a little: the bounds are wide
# enough for that and narrow enough to catch a broken estimator.
# Exits 77 (skipped) without apitrace, glmark2 or xvfb-run.
# usage: test_frame_sample.sh RASTSIM SOURCE_DIR [SCENE FRAMES SIZE]
set -euo pipefail
RASTSIM="$1"; SRC="$2"; SCENE="${3:-bump}"; FRAMES="${4:-24}"; SIZE="${5:-320x240}"
for tool in apitrace glmark2 xvfb-run; do
  command -v "$tool" >/dev/null || { echo "skip: '$tool' not installed (scripts/setup.sh installs it)"; exit 77; }
done
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
"$SRC/scripts/capture_glmark2" --size "$SIZE" "$SCENE" "$FRAMES" "$TMP/cap.trace"
"$RASTSIM" import-apitrace "$TMP/cap.trace" -o "$TMP/cap.rs.trace.zst" --config-out "$TMP/cap.set" >/dev/null
sets=()
while read -r line; do [ -n "$line" ] && sets+=(--set "$line"); done <"$TMP/cap.set"
common=(--config "$SRC/configs/d3d11.toml" --set "display.width=${SIZE%x*}" --set "display.height=${SIZE#*x}"
        "${sets[@]}" --scene "$TMP/cap.rs.trace.zst" -q)
"$RASTSIM" simulate "${common[@]}" --stats "$TMP/full.json"
"$RASTSIM" simulate "${common[@]}" --frame-sample 0.05 --stats "$TMP/fs.json"
python3 - "$TMP/full.json" "$TMP/fs.json" <<'PY'
import json, sys
full, fs = (json.load(open(p)) for p in sys.argv[1:3])


def problems(cycles, frame_cycles):
    """What is wrong with the frame-sampled run against a full run of `cycles` cycles."""
    out = []
    n = len(frame_cycles)
    if sum(frame_cycles) != cycles:
        out.append(f"the full run's frames[].cycles sum to {sum(frame_cycles)}, not its {cycles} cycles")
    if not fs["frames_simulated"] < fs["frames_total"] == n:
        out.append(f"{fs['frames_simulated']} of {fs['frames_total']} frames simulated (the full run: {n})")
    if not fs["cycles_ci_low"] <= cycles <= fs["cycles_ci_high"]:
        out.append(f"interval [{fs['cycles_ci_low']:.0f}, {fs['cycles_ci_high']:.0f}] misses {cycles}")
    err = (fs["cycles"] - cycles) / cycles
    if abs(err) > 0.05:
        out.append(f"estimate {fs['cycles']} is {100 * err:+.2f} % off {cycles}")
    for k, y in zip(fs["frames_simulated_list"], fs["frames_simulated_cycles"]):
        e = (y - frame_cycles[k]) / frame_cycles[k]
        if k != n - 1 and abs(e) > 0.10:
            out.append(f"frame {k}: {y:.0f} cycles measured, {frame_cycles[k]} in the full run ({100 * e:+.2f} %)")
    return out


ys = [f["cycles"] for f in full["frames"]]
bad = problems(full["cycles"], ys)
err = (fs["cycles"] - full["cycles"]) / full["cycles"]
print(f"full {full['cycles']} cycles, {len(ys)} frames; frame-sampled {fs['cycles']} ({100 * err:+.2f} %), "
      f"[{fs['cycles_ci_low']:.0f}, {fs['cycles_ci_high']:.0f}], {fs['frames_simulated']} frames simulated "
      f"{fs['frames_simulated_list']}")
if not full.get("frame_boundary") == fs.get("frame_boundary") == "rop":
    bad.append(f"frame boundaries: full run {full.get('frame_boundary')}, frame-sampled {fs.get('frame_boundary')}")
if sum(f["cycles_fetch"] for f in full["frames"]) != full["cycles"]:
    bad.append("the full run's frames[].cycles_fetch do not sum to its cycles")
for b in bad:
    print("FAIL:", b)
# The checks must fail on a wrong full run: 1.3x the cycles, every frame scaled alike.
wrong = [round(1.3 * y) for y in ys]
if not problems(sum(wrong), wrong):
    print("FAIL: the checks accept a full run of 1.3x the cycles")
    bad.append("1.3x")
sys.exit(1 if bad else 0)
PY
