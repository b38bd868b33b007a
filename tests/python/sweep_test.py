#!/usr/bin/python3
"""rockcut sweep with --seeds, run as a user would: a 4 ms dry cut at two tool speeds and two
specimen seeds (about 3 s). Checks the folder layout, that every run used its seed, that
sweep_mean.csv holds the mean, min and max of each value's runs, that the figures are drawn, and
that --plot-only finds the seeds again from the folders.

  tests/python/sweep_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line and CSV reading

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SWEEP = [os.path.join(ROOT, "scripts", "rockcut"), "sweep"]
CASE = os.path.join(ROOT, "cases", "cutting", "dry_reduced.pbtxt")
ARGS = None


class SweepWithSeeds(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "sweep_seeds")
        shutil.rmtree(cls.out, ignore_errors=True)
        cls.run_ = subprocess.run(
            # The steady part from 1 mm: these short runs have forces to draw.
            [*SWEEP, CASE, "--vary", "dem.tool.velocity_m_s=0.5,1", "--seeds", "3,5",
             "--set", "time.end_time_s=0.004", "--set", "dem.tool.steady_after_m=0.001",
             "--jobs", "2", "--out", cls.out,
             "--coupler", ARGS.coupler],
            capture_output=True, text=True, timeout=240)

    def test_runs_every_value_and_seed_into_its_folder(self):
        self.assertEqual(self.run_.returncode, 0, self.run_.stdout + self.run_.stderr)
        for v in ("0.5", "1"):
            for s in (3, 5):
                d = os.path.join(self.out, f"dem.tool.velocity_m_s={v}", f"seed={s}")
                self.assertTrue(os.path.isfile(os.path.join(d, "summary.json")), d)
                with open(os.path.join(d, "log.txt")) as f:
                    self.assertIn(f"dem.specimen.seed={s}", f.readline())

    def test_sweep_csv_has_one_row_per_run_with_its_seed(self):
        rows = harness.read_csv(os.path.join(self.out, "sweep.csv"))
        self.assertEqual([(r["dem.tool.velocity_m_s"], r["seed"]) for r in rows],
                         [("0.5", "3"), ("0.5", "5"), ("1", "3"), ("1", "5")])
        # Different specimens: the seeds really reached the runs (disc counts differ).
        counts = {r["seed"]: r["particles"] for r in rows}
        self.assertNotEqual(counts["3"], counts["5"])

    def test_sweep_mean_csv_is_the_mean_min_and_max_of_the_seeds(self):
        runs = harness.read_csv(os.path.join(self.out, "sweep.csv"))
        means = harness.read_csv(os.path.join(self.out, "sweep_mean.csv"))
        self.assertEqual([m["dem.tool.velocity_m_s"] for m in means], ["0.5", "1"])
        for m in means:
            mine = [r for r in runs if r["dem.tool.velocity_m_s"] == m["dem.tool.velocity_m_s"]]
            self.assertEqual(int(m["runs"]), 2)
            self.assertEqual(int(m["runs_ok"]), 2)
            for key in ("breaks_tensile", "breaks_shear", "particles"):
                v = [float(r[key]) for r in mine]
                # Exact up to the CSV's repr round trip of a mean of two numbers.
                self.assertAlmostEqual(float(m[key]), sum(v) / 2, delta=1e-9 * max(1, abs(v[0])))
                self.assertEqual(float(m[key + "_min"]), min(v))
                self.assertEqual(float(m[key + "_max"]), max(v))

    def test_figures_are_drawn(self):
        for png in ("fig08_forces.png", "breaks_fraction.png", "chips.png",
                    "fig11_damage_0.5.png", "fig12_damage_1.png"):
            path = os.path.join(self.out, png)
            self.assertTrue(os.path.isfile(path) and os.path.getsize(path) > 1000, path)

    def test_plot_only_finds_the_seeds_from_the_folders(self):
        os.remove(os.path.join(self.out, "sweep_mean.csv"))
        r = subprocess.run([*SWEEP, "--plot-only", "--out", self.out], capture_output=True,
                           text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(len(harness.read_csv(os.path.join(self.out, "sweep_mean.csv"))), 2)
        self.assertEqual(len(harness.read_csv(os.path.join(self.out, "sweep.csv"))), 4)

    def test_bad_seeds_are_refused_before_anything_runs(self):
        out = os.path.join(ARGS.tmp, "sweep_bad_seeds")
        shutil.rmtree(out, ignore_errors=True)
        r = subprocess.run([*SWEEP, CASE, "--vary", "water_depth_m=0", "--seeds", "1,1",
                            "--out", out, "--coupler", ARGS.coupler],
                           capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 2)
        self.assertIn("--seeds", r.stderr)
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
