# SPDX-License-Identifier: Apache-2.0
"""What the benchmark and plot scripts share: the repository root, one `rastsim` run's
--stats JSON, whole-process wall time and peak memory through GNU time, the random
triangle scenes of the fidelity benchmarks, and the command line of the two-argument
plot scripts. Imported by those scripts (scripts/ is on sys.path when one runs)."""
import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent  # the repository (scripts/..)
TIME = "/usr/bin/time"  # GNU time (Debian package `time`, scripts/setup.sh)
PEAK_GOAL_MB = 64  # the peak resident set every cost benchmark run must stay under


def run_stats(cmd):
    """The --stats JSON of one run of cmd (a rastsim command line without --stats); on
    failure, exits with `SCRIPT: CMD failed:` and the run's stderr."""
    prog = os.path.basename(sys.argv[0])
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        try:
            r = subprocess.run([str(c) for c in cmd] + ["--stats", f.name], capture_output=True, text=True)
        except FileNotFoundError:
            sys.exit("%s: %s not found (build it: ninja -C build rastsim)" % (prog, cmd[0]))
        if r.returncode != 0:
            sys.exit("%s: %s failed:\n%s" % (prog, " ".join(map(str, cmd)), r.stderr or r.stdout))
        return json.load(open(f.name))


def random_triangles(path, width, height, seed, n, sizes, comment):
    """Writes a trace of n seeded random triangles over a width x height viewport (after a
    black clear): each centred at a uniform point, its vertices within +-size of it
    (size drawn from `sizes`, clamped to the viewport), per-vertex depth and colour."""
    rng = random.Random(seed)
    lines = [comment, "viewport %d %d" % (width, height), "clear 0 0 0"]
    for _ in range(n):
        cx, cy, size = rng.uniform(0, width), rng.uniform(0, height), rng.choice(sizes)
        verts = []
        for _ in range(3):
            x = min(max(cx + rng.uniform(-size, size), 0), width)
            y = min(max(cy + rng.uniform(-size, size), 0), height)
            verts.append("%.3f %.3f %.3f %d %d %d" % (x, y, rng.random(), rng.randrange(256), rng.randrange(256),
                                                      rng.randrange(256)))
        lines.append("tri " + " ".join(verts))
    Path(path).write_text("\n".join(lines) + "\n")


def rastsim_parser(doc, config, whole_doc=False):
    """An argument parser with --rastsim (default build/rastsim) and --config (default
    configs/CONFIG.toml); described by the docstring's first line, or by all of it."""
    if whole_doc:
        ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    else:
        ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--rastsim", default=os.path.join(ROOT, "build", "rastsim"))
    ap.add_argument("--config", default=os.path.join(ROOT, "configs", config + ".toml"))
    return ap


# ---- whole-process cost: wall time and peak memory (bench_scale, bench_stream) ----

def cost_args(doc, list_flag, list_default):
    """The cost benchmarks' options: --rastsim, --config (d3d11), --runs and the list of
    sizes or counts (`list_flag`); exits when GNU time is missing."""
    ap = rastsim_parser(doc, "d3d11")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument(list_flag, default=list_default)
    a = ap.parse_args()
    if not os.access(TIME, os.X_OK):
        sys.exit(f"{TIME} not found: install GNU time (Debian package `time`, scripts/setup.sh)")
    return a


def timed_run(cmd):
    """Wall seconds and peak resident set in kB of one run of cmd."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as tf:
        t0 = time.perf_counter()
        subprocess.run([TIME, "-o", tf.name, "-f", "%M"] + cmd, check=True, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        return wall, int(tf.read().strip().splitlines()[-1])


def render_and_simulate_cost(a, args, stats_path):
    """{command: (median wall seconds, largest peak kB)} of `a.runs` runs each of
    `rastsim render` and `rastsim simulate` on a.config with `args`, stats only."""
    res = {}
    for cmd in ("render", "simulate"):
        runs = [timed_run([a.rastsim, cmd, "-c", a.config] + args + ["-q", "--stats", stats_path])
                for _ in range(a.runs)]
        res[cmd] = (statistics.median(w for w, _ in runs), max(m for _, m in runs))
    return res


def print_cost_table(first_cell, heads, res, keys, wall_format):
    """The Markdown table of render's and simulate's wall time and peak memory, one
    column a key (heads: the column titles; res: {(command, key): (wall, peak kB)})."""
    print(f"| {first_cell} | " + " | ".join(heads) + " |")
    print("|---|" + "---:|" * len(keys))
    for cmd in ("render", "simulate"):
        cells = [f"{res[cmd, k][0]:{wall_format}} s, {res[cmd, k][1] / 1024:.0f} MB" for k in keys]
        print(f"| `{cmd}` wall, peak memory | " + " | ".join(cells) + " |")


def report_goals(res, keys, wall_goal):
    """Prints, after a blank line, one line a command (render, simulate): its wall-time
    goal, wall_goal(wall at keys[0], wall at keys[-1]) -> (met, text), and its peak
    memory goal (under PEAK_GOAL_MB at every key). True when every goal is met."""
    ok = True
    print()
    for cmd in ("render", "simulate"):
        wall_ok, wall_text = wall_goal(res[cmd, keys[0]][0], res[cmd, keys[-1]][0])
        peak = max(res[cmd, k][1] for k in keys) / 1024
        ok &= wall_ok and peak < PEAK_GOAL_MB
        print(f"- `{cmd}`: {wall_text}; peak {peak:.0f} MB {'ok' if peak < PEAK_GOAL_MB else 'MISSED'} "
              f"(goal < {PEAK_GOAL_MB} MB)")
    return ok


# ---- plots ----

def plot_args(doc):
    """(IN, OUT) of a plot script called as `SCRIPT IN OUT`; prints the docstring and
    exits 0 for -h/--help, 2 for any other argument count."""
    if len(sys.argv) != 3 or sys.argv[1] in ("-h", "--help"):
        print(doc.strip())
        sys.exit(0 if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help") else 2)
    return sys.argv[1], sys.argv[2]


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no display)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
