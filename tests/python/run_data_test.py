#!/usr/bin/python3
"""rockcut.read_run and rockcut plot on a 4 ms dry reduced cut (about 2 s): the summary, the time
series, the frames and the breaks as NumPy arrays, checked against what the run says of itself.

  tests/python/run_data_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
import shutil
import subprocess
import unittest

import numpy as np

import harness  # tests/python/harness.py: the command line
import rockcut
from rockcut import runs

ROCKCUT = os.path.join(runs.REPO, "scripts", "rockcut")
ARGS = None


class ReadRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "read_run")
        shutil.rmtree(cls.out, ignore_errors=True)
        proc = runs.run(runs.case("cutting", "dry_reduced.pbtxt"), cls.out,
                        ["time.end_time_s=0.004", "output.frame_interval_s=0.001"], ARGS.coupler)
        assert proc.returncode == 0, proc.stderr
        cls.run_ = rockcut.read_run(cls.out)

    def test_summary_is_summary_json(self):
        self.assertEqual(self.run_.summary["status"], "completed")
        self.assertEqual(self.run_.summary["title"], "dry cutting, reduced block")

    def test_timeseries_are_arrays_of_one_length(self):
        ts = self.run_.timeseries
        lengths = {len(v) for v in ts.values()}
        self.assertEqual(len(lengths), 1)
        self.assertGreater(lengths.pop(), 10)
        self.assertTrue(np.all(np.diff(ts["time_s"]) > 0))
        # The tool moves at 1 m/s: its travel grows by the time elapsed.
        travel = ts["tool_travel_m"]
        self.assertAlmostEqual(travel[-1] - travel[0], ts["time_s"][-1] - ts["time_s"][0], places=9)

    def test_frames_hold_the_particles(self):
        frames = self.run_.frames
        self.assertEqual(len(frames), 5)  # t = 0, 1, 2, 3, 4 ms
        # A frame is written at the first step at or after its time: within one step of it.
        np.testing.assert_allclose(frames.times, [0.0, 0.001, 0.002, 0.003, 0.004],
                                   atol=self.run_.summary["dt_s"])
        self.assertEqual(frames.fields, ["damage", "position", "radius", "velocity"])
        last = frames[-1]
        n = self.run_.summary["particles"]
        self.assertEqual(last["position"].shape, (n, 2))
        self.assertEqual(last["radius"].shape, (n,))
        self.assertAlmostEqual(last.time_s, 0.004, delta=self.run_.summary["dt_s"])
        self.assertTrue(np.all((last["radius"] >= 0.0008) & (last["radius"] <= 0.0016)))
        # The first frame is the intact specimen; some bonds have broken by the last.
        self.assertEqual(float(frames[0]["damage"].max()), 0.0)
        self.assertGreater(float(last["damage"].max()), 0.0)
        self.assertEqual(list(frames.read(0, ("radius",))), ["radius"])

    def test_breaks_are_one_row_per_broken_bond(self):
        b = self.run_.breaks
        total = self.run_.summary["breaks_tensile"] + self.run_.summary["breaks_shear"]
        self.assertEqual(len(b["x_m"]), total)
        self.assertEqual(int((b["mode"] == 1).sum()), self.run_.summary["breaks_shear"])

    def test_scene_is_the_effective_scene(self):
        self.assertIn("tensile_strength_n_per_m: 26600", self.run_.scene)  # from the rock base
        self.assertIn("end_time_s: 0.004", self.run_.scene)                # the override

    def test_plot_draws_the_cut_and_refuses_a_folder_without_a_run(self):
        r = subprocess.run([ROCKCUT, "plot", self.out], capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        for png in ("force.png", "damage.png", "breaks.png"):
            self.assertGreater(os.path.getsize(os.path.join(self.out, png)), 1000, png)
        empty = os.path.join(ARGS.tmp, "read_run_empty")
        os.makedirs(empty, exist_ok=True)
        r = subprocess.run([ROCKCUT, "plot", empty], capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no run.h5", r.stderr)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
