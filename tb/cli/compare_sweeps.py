#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Compares two `rastsim sweep` CSVs: same columns, same rows in the same order, every
cell equal except the wall-time columns (wall_seconds, sim_wall_seconds,
simulated_cycles_per_second), which depend on the host. Prints the first differences.

usage: compare_sweeps.py A.csv B.csv    (exit 0 when they agree)
"""
import csv
import sys

WALL = {"wall_seconds", "sim_wall_seconds", "simulated_cycles_per_second"}


def main():
    a, b = ([r for r in csv.reader(open(p, newline=""))] for p in sys.argv[1:3])
    problems = []
    if not a or not b:
        problems.append("an empty file")
    elif a[0] != b[0]:
        problems.append("headers differ:\n  %s\n  %s" % (",".join(a[0]), ",".join(b[0])))
    elif len(a) != len(b):
        problems.append("%d rows against %d" % (len(a) - 1, len(b) - 1))
    else:
        keep = [i for i, c in enumerate(a[0]) if c not in WALL]
        for n, (ra, rb) in enumerate(zip(a[1:], b[1:]), 1):
            for i in keep:
                if ra[i] != rb[i]:
                    problems.append("row %d (%s), %s: %r against %r" % (n, ra[0], a[0][i], ra[i], rb[i]))
    for p in problems[:10]:
        print("compare_sweeps: " + p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
