#!/usr/bin/python3
"""rockcut compare, run as a user would, on sweep folders written here with chosen
summaries (no simulation: the script only reads summary.json files). Checks the means and ranges
over the seeds, the crossings of the shear fraction through 0.5 and through the middle of its
change against values worked out by hand,
the sweeps without a crossing, and that bad input is refused before anything is written.

  tests/python/compare_sweeps_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line and CSV reading

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
COMPARE = [os.path.join(ROOT, "scripts", "rockcut"), "compare"]
ARGS = None


def p_of(depth):
    """A made-up p_hydro, linear in depth like the real one (1e5 Pa + 1e4 Pa/m): 0 m -> 1e5 Pa,
    150 m -> 1.6e6 Pa, a factor 16, so the log-p interpolation has a round answer."""
    return 1e5 + 1e4 * depth


def write_sweep(out, runs, name="water_depth_m"):
    """runs: {depth: [(tensile, shear, Fh), ...] one per seed}."""
    shutil.rmtree(out, ignore_errors=True)
    for depth, seeds in runs.items():
        for seed, (tensile, shear, fh) in enumerate(seeds, start=1):
            d = os.path.join(out, f"{name}={depth}", f"seed={seed}")
            os.makedirs(d)
            with open(os.path.join(d, "summary.json"), "w") as f:
                json.dump({"breaks_tensile": tensile, "breaks_shear": shear,
                           "force_horizontal_mean_n_per_m": fh, "chip_area_mean_m2": 2e-5,
                           "hydrostatic_pressure_pa": p_of(float(depth))}, f)


def run(*args):
    return subprocess.run([*COMPARE, *args], capture_output=True, text=True, timeout=120)


class CompareSweeps(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = os.path.join(ARGS.tmp, "compare_sweeps")
        shutil.rmtree(cls.dir, ignore_errors=True)
        os.makedirs(cls.dir)
        # Crosses: the mean fraction is 0.25 at 0 m (seeds 0.2 and 0.3) and 0.75 at 150 m, so
        # halfway in log p: p = sqrt(1e5 * 1.6e6) = 4e5 Pa, i.e. 30 m. Linear in depth would
        # give 75 m, so the test tells the two apart.
        cls.crossing = os.path.join(cls.dir, "crossing")
        write_sweep(cls.crossing, {"0": [(80, 20, 1e5), (70, 30, 3e5)],
                                   "150": [(25, 75, 4e5), (25, 75, 4e5)]})
        cls.tensile = os.path.join(cls.dir, "ts=tensile")  # '=' in the folder's name
        write_sweep(cls.tensile, {"0": [(90, 10, 1e5)], "150": [(60, 40, 2e5)]})
        cls.shear = os.path.join(cls.dir, "shear")
        write_sweep(cls.shear, {"0": [(40, 60, 1e5)], "150": [(20, 80, 2e5)]})
        # Runs that failed or never ran (a seed folder without summary.json) are left out and
        # named.
        cls.partial = os.path.join(cls.dir, "partial")
        write_sweep(cls.partial, {"0": [(90, 10, 1e5)], "150": [(60, 40, 2e5)]})
        os.makedirs(os.path.join(cls.partial, "water_depth_m=150", "seed=9"))
        cls.falling = os.path.join(cls.dir, "falling")
        write_sweep(cls.falling, {"0": [(40, 60, 1e5)], "150": [(60, 40, 2e5)]})

    def test_the_crossing_means_and_ranges_are_tabled(self):
        csv_path = os.path.join(self.dir, "compare.csv")
        png = os.path.join(self.dir, "compare.png")
        r = run(f"{self.crossing}=A", self.tensile, f"{self.shear}=C", self.falling,
                "--csv", csv_path, "--plot", png)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        rows = harness.read_csv(csv_path)
        self.assertEqual([(x["label"], x["water_depth_m"], x["runs"]) for x in rows],
                         [("A", "0", "2"), ("A", "150", "2"), ("ts=tensile", "0", "1"),
                          ("ts=tensile", "150", "1"), ("C", "0", "1"), ("C", "150", "1"),
                          ("falling", "0", "1"), ("falling", "150", "1")])
        a0 = rows[0]
        # Mean and range over the two seeds at 0 m.
        self.assertAlmostEqual(float(a0["shear_fraction"]), 0.25, places=12)
        self.assertAlmostEqual(float(a0["shear_fraction_min"]), 0.2, places=12)
        self.assertAlmostEqual(float(a0["shear_fraction_max"]), 0.3, places=12)
        self.assertAlmostEqual(float(a0["force_horizontal_mean_n_per_m"]), 2e5, places=6)
        self.assertAlmostEqual(float(a0["force_horizontal_min_n_per_m"]), 1e5, places=6)
        self.assertAlmostEqual(float(a0["force_horizontal_max_n_per_m"]), 3e5, places=6)
        # The crossing of 0.5, worked out above; here also the half-way level (0.25 + 0.75) / 2.
        self.assertAlmostEqual(float(a0["majority_pressure_pa"]), 4e5, delta=1e-6)
        self.assertAlmostEqual(float(a0["majority_depth_m"]), 30.0, places=9)
        self.assertAlmostEqual(float(a0["half_way_fraction"]), 0.5, places=12)
        self.assertAlmostEqual(float(a0["half_way_depth_m"]), 30.0, places=9)
        self.assertIn("shear breaks the majority (shear fraction 0.50): from 30 m, p_hydro 0.40 MPa",
                      r.stdout)
        # No majority either way: said, and left empty in the CSV; the half-way crossing is there
        # all the same (0.1 -> 0.4: level 0.25, again half-way in log p, 30 m; 0.6 -> 0.8: 0.7).
        self.assertIn("below 0.50 at every depth (at most 0.40)", r.stdout)
        self.assertIn("above 0.50 already at 0 m (0.60)", r.stdout)
        self.assertEqual([x["majority_depth_m"] for x in rows[2:6]], ["", "", "", ""])
        for row, level in ((rows[2], 0.25), (rows[4], 0.7)):
            self.assertAlmostEqual(float(row["half_way_fraction"]), level, places=12)
            self.assertAlmostEqual(float(row["half_way_depth_m"]), 30.0, places=9)
        # A fraction that falls with depth has no half-way crossing.
        self.assertIn("half-way: no crossing (the shear fraction does not rise with depth)",
                      r.stdout)
        self.assertEqual(rows[6]["half_way_depth_m"], "")
        self.assertGreater(os.path.getsize(png), 10000)

    def test_runs_without_a_summary_are_left_out_and_named(self):
        csv_path = os.path.join(self.dir, "partial.csv")
        r = run(self.partial, "--csv", csv_path)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("left out, no summary.json (failed or not run): 0 m seed 9, 150 m seed 9",
                      r.stdout)
        rows = harness.read_csv(csv_path)
        self.assertEqual([(x["water_depth_m"], x["runs"]) for x in rows], [("0", "1"), ("150", "1")])
        self.assertAlmostEqual(float(rows[1]["shear_fraction"]), 0.4, places=12)

    def test_bad_input_is_refused_before_anything_is_written(self):
        other = os.path.join(self.dir, "other")
        write_sweep(other, {"0.5": [(1, 1, 1.0)]}, name="dem.tool.velocity_m_s")
        empty = os.path.join(self.dir, "empty")
        shutil.rmtree(empty, ignore_errors=True)
        os.makedirs(os.path.join(empty, "water_depth_m=0"))
        csv_path = os.path.join(self.dir, "refused.csv")
        cases = [([self.crossing, other], "varies dem.tool.velocity_m_s, not water_depth_m"),
                 ([self.crossing, empty], "holds no run with a summary.json"),
                 ([self.crossing, os.path.join(self.dir, "nowhere")], "no such folder"),
                 ([f"{self.crossing}=X", f"{self.shear}=X"], "two sweeps share a label")]
        for sweeps, reason in cases:
            r = run(*sweeps, "--csv", csv_path, "--plot", csv_path + ".png")
            self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
            self.assertIn(reason, r.stderr)
            self.assertFalse(os.path.exists(csv_path))
            self.assertFalse(os.path.exists(csv_path + ".png"))


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
