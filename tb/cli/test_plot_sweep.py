#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Checks scripts/plot_sweep on hand-written sweep CSVs: one line per value of a second
swept key, a constant (fixed --set) column not taken for a swept key, more than two
swept keys refused by name, the title after the x key, a linear y axis for a range under
a factor of two and a log one above, and one-line errors (no traceback) for a missing
file or column.

usage: test_plot_sweep.py PLOT_SWEEP_SCRIPT
"""
import importlib.machinery
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")

SCRIPT = os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else None
HEADER = "scene,raster.tile_size,raster.samples,raster.depth_func,level,config_hash,status,cycles\n"


def load_script():
    loader = importlib.machinery.SourceFileLoader("plot_sweep", SCRIPT)
    spec = importlib.util.spec_from_loader("plot_sweep", loader)
    mod = importlib.util.module_from_spec(spec)
    loader.exec_module(mod)
    return mod


class PlotSweep(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.plot = load_script()

    def tearDown(self):
        self.dir.cleanup()

    def csv(self, rows, header=HEADER):
        path = os.path.join(self.dir.name, "s.csv")
        with open(path, "w") as f:
            f.write(header + "".join(rows))
        return path

    def run_script(self, *args):
        return subprocess.run([SCRIPT, *args], capture_output=True, text=True)

    def axes_of(self, csv_path, *extra):
        """Runs the script's main() in this process and returns the axes it drew."""
        import matplotlib.pyplot as plt

        saved = sys.argv
        sys.argv = ["plot_sweep", csv_path, os.path.join(self.dir.name, "out"), *extra]
        try:
            self.plot.main()
        finally:
            sys.argv = saved
        return plt.gcf().axes[0]

    def test_second_key_one_line_per_value(self):
        # 3 tile sizes x 2 sample counts, depth_func fixed (constant): two lines.
        rows = ["t.trace,%d,%d,less,systemc,h%d%d,ok,%d\n" % (t, s, t, s, 1000 * s + t)
                for t in (8, 16, 32) for s in (1, 4)]
        ax = self.axes_of(self.csv(rows))
        self.assertEqual(len(ax.lines), 2)
        self.assertEqual(sorted(line.get_label() for line in ax.lines), ["raster.samples=1", "raster.samples=4"])
        for line in ax.lines:  # each line holds its own value's points, in x order
            s = 1 if line.get_label().endswith("=1") else 4
            self.assertEqual(list(line.get_xdata()), [8, 16, 32])
            self.assertEqual(list(line.get_ydata()), [1000 * s + 8, 1000 * s + 16, 1000 * s + 32])
        self.assertIn("raster.tile_size", ax.get_title())
        self.assertEqual(ax.get_xlabel(), "raster.tile_size")

    def test_title_names_the_x_key(self):
        rows = ["t.trace,16,%d,less,systemc,h%d,ok,%d\n" % (s, s, 100 * s) for s in (1, 2, 4, 8)]
        ax = self.axes_of(self.csv(rows))
        self.assertEqual(ax.get_xlabel(), "raster.samples")
        self.assertIn("raster.samples", ax.get_title())
        self.assertNotIn("tile", ax.get_title())

    def test_small_range_linear_large_range_log(self):
        # 0.7 % apart: linear; 8x apart: log.
        small = ["t.trace,%d,1,less,systemc,h%d,ok,%d\n" % (t, t, c) for t, c in ((8, 10070), (16, 10000))]
        self.assertEqual(self.axes_of(self.csv(small)).get_yscale(), "linear")
        large = ["t.trace,%d,1,less,systemc,h%d,ok,%d\n" % (t, t, c) for t, c in ((8, 8000), (16, 1000))]
        self.assertEqual(self.axes_of(self.csv(large)).get_yscale(), "log")

    def test_three_swept_keys_refused_by_name(self):
        rows = ["t.trace,%d,%d,%s,systemc,h%d%d%s,ok,1\n" % (t, s, d, t, s, d)
                for t in (8, 16) for s in (1, 4) for d in ("less", "always")]
        r = self.run_script(self.csv(rows), os.path.join(self.dir.name, "out"))
        self.assertNotEqual(r.returncode, 0)
        self.assertNotIn("Traceback", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        for key in ("raster.tile_size", "raster.samples", "raster.depth_func"):
            self.assertIn(key, r.stderr)

    def test_missing_file_and_column_one_line(self):
        out = os.path.join(self.dir.name, "out")
        missing = os.path.join(self.dir.name, "nope.csv")
        rows = ["t.trace,%d,1,less,systemc,h%d,ok,%d\n" % (t, t, t) for t in (8, 16)]
        for args, word in (([missing, out], "nope.csv"), ([self.csv(rows), out, "--y", "fragments"], "fragments")):
            r = self.run_script(*args)
            self.assertNotEqual(r.returncode, 0)
            self.assertNotIn("Traceback", r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(word, r.stderr)


if __name__ == "__main__":
    unittest.main()
