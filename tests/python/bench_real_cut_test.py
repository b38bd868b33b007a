#!/usr/bin/python3
"""bench/bench_real_cut.py and bench/scaling_model.py: the cached state, the stretch's figures and
the scaling model, run as a user runs them (on the reduced scenes, in seconds).

  tests/python/bench_real_cut_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import math
import os
import re
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bench_real_cut  # bench/ is on PYTHONPATH (tests/CMakeLists.txt)
import scaling_model


class ScalingModel(unittest.TestCase):
    def test_amdahl_from_two_points(self):
        # 1 ms serial and 4 ms parallel: 5 ms on one thread, 3 ms on two.
        s, q = scaling_model.fit(5e-3, 3e-3)
        self.assertAlmostEqual(s, 1e-3)
        self.assertAlmostEqual(q, 4e-3)
        self.assertAlmostEqual(scaling_model.predict(s, q, 16), 1e-3 + 4e-3 / 16)
        # Slower on two threads: serial at its two-thread cost.
        self.assertEqual(scaling_model.fit(1e-3, 1.2e-3), (1.2e-3, 0.0))
        # More than twice as fast on two (two cores' caches): parallel, from the two-thread cost.
        self.assertEqual(scaling_model.fit(5e-3, 2e-3), (0.0, 4e-3))

    def test_model_of_a_step(self):
        one = {"dem.bonds": 4e-3, "dem.barrier": 0.0, "service": 1e-4, "rest": 5e-5}
        two = {"dem.bonds": 2e-3, "dem.barrier": 1e-4, "service": 1e-4, "rest": 5e-5}
        parts = scaling_model.model(one, two)
        # Perfectly parallel bonds, the barrier b (2/t) log2(t), the service and the rest serial.
        self.assertAlmostEqual(scaling_model.step_cost(parts, 1), 4e-3 + 1.5e-4)
        self.assertAlmostEqual(scaling_model.step_cost(parts, 2), 2e-3 + 1e-4 + 1.5e-4)
        self.assertAlmostEqual(scaling_model.step_cost(parts, 64),
                               4e-3 / 64 + 1e-4 * 2 / 64 * math.log2(64) + 1.5e-4)

    def test_another_coupling_interval(self):
        # Measured at N = 1: the fluid's passes, the service and the rest happen once per
        # exchange, a quarter as often at N = 4; the DEM's phases and the fluid's refreshes (per
        # distance travelled) stay.
        costs = {"dem.bonds": 4e-3, "fluid.passes": 2e-3, "fluid.geometry": 1e-3,
                 "fluid.boundary": 1e-4, "service": 8e-4, "rest": 4e-4}
        moved = scaling_model.at_interval(costs, 1, 4)
        self.assertEqual(moved["dem.bonds"], 4e-3)
        self.assertEqual(moved["fluid.geometry"], 1e-3)
        self.assertEqual(moved["fluid.boundary"], 1e-4)
        self.assertAlmostEqual(moved["fluid.passes"], 5e-4)
        self.assertAlmostEqual(moved["service"], 2e-4)
        self.assertAlmostEqual(moved["rest"], 1e-4)
        # And back: N = 4's costs at N = 1 are the ones measured there.
        for key, value in scaling_model.at_interval(moved, 4, 1).items():
            self.assertAlmostEqual(value, costs[key])

    def test_the_interval_is_the_runs_own_and_one_per_fit(self):
        self.assertEqual(scaling_model.measured_interval([{}, {"coupling_interval": 1}]), 1)
        self.assertEqual(scaling_model.measured_interval([{"coupling_interval": 4}]), 4)
        with self.assertRaises(SystemExit):
            scaling_model.measured_interval([{"coupling_interval": 1}, {"coupling_interval": 4}])

    def test_the_stored_16_core_runs_at_n_4(self):
        # The 16-core machine's saturated runs (N = 1), moved to the scene's N = 4: the command
        # prints the prediction and refuses to hold it against runs made at N = 1.
        r = subprocess.run(
            ["/usr/bin/python3", os.path.join(ROOT, "bench", "scaling_model.py"),
             os.path.join(ROOT, "docs", "record", "results", "scaling_16_cores_saturated.json"),
             "--interval", "4", "--cores", "16", "--check", "t16:16"],
            capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("measured at N = 1, predicted at N = 4", r.stdout)
        self.assertIn("t16: measured at N = 1, not at 4", r.stdout)
        sixteen = float(re.search(r"16 cores: ([0-9.]+) ms/step", r.stdout).group(1))
        # Below N = 1's model (3.27 ms) by what the exchanges cost, above the DEM's own step.
        self.assertGreater(sixteen, 1.0)
        self.assertLess(sixteen, 2.5)


class RealCut(unittest.TestCase):
    def test_the_cache_key_holds_in_any_checkout(self):
        # The effective scene is named by its path in the tree, not where the tree lies, so the
        # cached states' keys (and the states) hold for a checkout elsewhere.
        text = bench_real_cut.effective_scene(
            os.path.relpath(ARGS.coupler), "cases/cutting/saturated_reduced_long.pbtxt", [])
        self.assertTrue(text.startswith("cases/cutting/saturated_reduced_long.pbtxt: ok"),
                        text[:200])
        self.assertNotIn(ROOT, text)

    def test_the_state_is_made_once_and_the_stretch_split(self):
        tmp = os.path.join(ARGS.tmp, "bench_real_cut")
        shutil.rmtree(tmp, ignore_errors=True)
        cache, out = os.path.join(tmp, "cache"), os.path.join(tmp, "runs.json")
        argv = ["/usr/bin/python3", os.path.join(ROOT, "bench", "bench_real_cut.py"),
                "--coupler", ARGS.coupler, "--scale", "reduced", "--damping", "local",
                "--scene", "saturated", "--depth", "0", "--at-mm", "2", "--stretch-mm", "0.5",
                "--repeat", "1", "--cache", cache, "--json", out,
                "--variant", "t1:dem.threads=1,fluid.threads=1,coupling.overlap=off",
                "--variant", "t2:dem.threads=2,fluid.threads=2,coupling.overlap=off"]
        first = subprocess.run(argv, capture_output=True, text=True, timeout=240)
        self.assertEqual(first.returncode, 0, first.stdout + first.stderr)
        self.assertIn("making the state at 2 mm of cases/cutting/saturated_reduced_long.pbtxt",
                      first.stdout)
        self.assertEqual(len(os.listdir(cache)), 1)
        self.assertIn("fluid.passes", first.stdout)  # the per-step medians of every part
        # The same variants by their shorthand, and one overlapping.
        argv = argv[:argv.index("--variant")] + ["--threads", "1,2", "--overlap-threads", "2"]
        second = subprocess.run(argv, capture_output=True, text=True, timeout=240)
        self.assertEqual(second.returncode, 0, second.stdout + second.stderr)
        self.assertNotIn("making the state", second.stdout)  # the cached one
        with open(out) as f:
            runs = json.load(f)
        self.assertEqual(sorted(r["variant"] for r in runs), ["o2", "t1", "t2"])
        self.assertFalse(os.path.exists(out + ".part"))
        for r in runs:
            # 0.5 mm at 1 m/s: 0.5 ms of the cut, thousands of steps.
            self.assertGreater(r["steps"], 1000)
            self.assertAlmostEqual(r["ms_per_step"], 1e3 * r["wall_s"] / r["steps"])
            self.assertGreater(r["phases"]["dem"]["bonds"], 0.0)
            self.assertGreater(r["phases"]["fluid"]["passes"], 0.0)
            # Each module's busy time within the stretch's wall, every part non-negative; taking
            # turns the two never run at once, so their sum is within it too (overlapping, the
            # DEM's forces after its reply run beside the fluid's step and are counted twice).
            for who in ("dem", "fluid"):
                self.assertLessEqual(r[who + "_busy_s"], r["wall_s"] * 1.001)
            if r["variant"].startswith("t"):
                self.assertLessEqual(r["dem_busy_s"] + r["fluid_busy_s"], r["wall_s"] * 1.001)
            self.assertGreaterEqual(r["own_s"], 0.0)
        model = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "bench", "scaling_model.py"),
                                out, "--cores", "2,64", "--check", "t2:2,t4:4"],
                               capture_output=True, text=True)
        self.assertEqual(model.returncode, 0, model.stderr)
        self.assertIn("64 cores:", model.stdout)
        # Held against what was measured. t2 is one of the two points the model is fitted to, so
        # it agrees but for a negative rest (waits shorter than the clocks' overlap), taken as 0.
        m = re.search(r"t2 on 2 threads: model ([0-9.]+) ms/step, measured ([0-9.]+) "
                      r"\(model/measured ([0-9.]+)\)", model.stdout)
        self.assertIsNotNone(m, model.stdout)
        self.assertAlmostEqual(float(m.group(3)), 1.0, delta=0.05)
        self.assertIn("t4: not measured", model.stdout)
        bad = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "bench", "bench_real_cut.py"),
                              "--threads", "0,2"], capture_output=True, text=True)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("expected thread counts", bad.stderr)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
