#!/usr/bin/python3
"""bench/bench_whole_cut.py: the per-window wall read off a run's progress lines, and the whole
driver run as a user runs it (the reduced scenes, cut short, in seconds).

  tests/python/bench_whole_cut_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bench_whole_cut  # bench/ is on PYTHONPATH (tests/CMakeLists.txt)


def progress_log(lines):
    """A run's log with progress lines at (step, wall) and dt 1e-6 s, as the coupler prints them."""
    text = "chosen dt = 1e-06 s\n"
    for step, wall in lines:
        text += "t = %.4g / 0.1 s  step %d / 100000  wall %.1f s  ETA 1.0 s\n" % (
            step * 1e-6, step, wall)
    return text


class Windows(unittest.TestCase):
    def test_per_step_wall_of_each_window_from_the_progress_lines(self):
        # 1 ms per step up to step 40,000, then 2 ms: lines every 2,500 steps. With the tool 1 mm
        # before the block at 1 m/s and dt 1 us, travel x mm is step 1000 (x + 1).
        lines, wall = [], 0.0
        for step in range(2500, 100001, 2500):
            wall += 2.5 if step <= 40000 else 5.0
            lines.append((step, wall))
        points = bench_whole_cut.progress_points(progress_log(lines))
        self.assertEqual(points[0], (0.0, 0, 0.0))
        self.assertEqual(points[-1][1:], (100000, 160.0))
        rows = bench_whole_cut.windows(points, 100000, 160.0, 1e-6, 1e-3, 1.0, [0, 19, 39, 59])
        # 0-19 mm: steps 1000-20000; 19-39: 20000-40000 (1 ms); 39-59: 40000-60000 (2 ms);
        # 59 mm to the end: 60000-100000 (2 ms).
        self.assertEqual([(a, b) for a, b, _ in rows], [(0, 19), (19, 39), (39, 59), (59, None)])
        for (_, _, ms), want in zip(rows, [1.0, 1.0, 2.0, 2.0]):
            self.assertAlmostEqual(ms, want)

    def test_a_window_the_lines_cannot_place_is_left_out(self):
        # One line half way: the 10-20 mm window's ends lie between lines 50,000 steps apart.
        points = bench_whole_cut.progress_points(progress_log([(50000, 50.0)]))
        rows = bench_whole_cut.windows(points, 100000, 100.0, 1e-6, 1e-3, 1.0, [10, 20])
        self.assertEqual(rows, [])
        # Windows longer than five such gaps are placed.
        lines = [(s, s * 1e-3) for s in range(1000, 100001, 1000)]
        points = bench_whole_cut.progress_points(progress_log(lines))
        rows = bench_whole_cut.windows(points, 100000, 100.0, 1e-6, 1e-3, 1.0, [10, 20])
        self.assertEqual([(a, b) for a, b, _ in rows], [(10, 20), (20, None)])


    def test_segments_of_a_resumed_run_join_at_its_checkpoint(self):
        # 1 ms per step throughout. The first segment logs to step 5000 and stops; the second
        # resumes from the checkpoint at step 4000, its wall restarting at 0 and its first 1000
        # steps redoing those after the checkpoint.
        first = progress_log([(s, s * 1e-3) for s in range(1000, 5001, 1000)])
        second = ("resume     from /a b/checkpoints/checkpoint_000000004000.h5 (step 4000, "
                  "t = 0.004 s; read in 0.01 s)\n" +
                  progress_log([(s, (s - 4000) * 1e-3) for s in range(5000, 9001, 1000)]))
        log = bench_whole_cut.SEGMENT + first + bench_whole_cut.SEGMENT + second
        points = bench_whole_cut.joined_points(log)
        self.assertEqual([p[1] for p in points], [0, 1000, 2000, 3000, 5000, 6000, 7000, 8000, 9000])
        for _, step, wall in points:
            self.assertAlmostEqual(wall, step * 1e-3)
        # One segment alone is its own lines.
        self.assertEqual(bench_whole_cut.joined_points(bench_whole_cut.SEGMENT + first),
                         bench_whole_cut.progress_points(first))


class WholeCut(unittest.TestCase):
    def test_runs_one_after_the_other_then_bench_dem(self):
        tmp = os.path.join(ARGS.tmp, "bench_whole_cut")
        shutil.rmtree(tmp, ignore_errors=True)
        os.makedirs(tmp)
        out = os.path.join(tmp, "whole.json")
        bench_dem = os.path.join(os.path.dirname(ARGS.coupler), "bench_dem")
        argv = ["/usr/bin/python3", os.path.join(ROOT, "bench", "bench_whole_cut.py"),
                "--coupler", ARGS.coupler, "--scale", "reduced", "--damping", "local",
                "--set", "time.end_time_s=0.003", "--json", out,
                "--keep", os.path.join(tmp, "runs")]
        if not os.path.exists(bench_dem):  # a build without Google Benchmark
            argv.append("--no-bench-dem")
        p = subprocess.run(argv, capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with open(out) as f:
            result = json.load(f)
        dry, saturated = result["runs"]
        self.assertIsNone(dry["depth_m"])
        self.assertEqual(saturated["depth_m"], 0.0)
        for run in (dry, saturated):
            # 2 mm of cut after the 1 mm gap: thousands of steps, each with its own summary.
            self.assertGreater(run["steps"], 1000)
            self.assertAlmostEqual(run["ms_per_step"], 1e3 * run["wall_s"] / run["steps"])
            self.assertTrue(os.path.exists(os.path.join(
                tmp, "runs", "dry" if run["depth_m"] is None else "saturated_0m", "run.h5")))
        self.assertAlmostEqual(saturated["wall_over_dry"], saturated["wall_s"] / dry["wall_s"])
        # The list work of each run, from its summary.json: the DEM's in both, the fluid's in
        # the saturated one only.
        for run in (dry, saturated):
            self.assertGreater(run["dem_neighbour_rebuilds"], 0)
            self.assertLess(run["dem_neighbour_rebuilds"], run["steps"])
        self.assertNotIn("fluid_geometry_updates", dry)
        self.assertGreaterEqual(saturated["fluid_geometry_updates"], 1)
        self.assertIn("DEM lists rebuilt every", p.stdout)
        self.assertIn("fluid geometry refreshed every", p.stdout)
        # The same runs taken further with --resume: each continues from its end-of-run checkpoint
        # (a second segment in its log) instead of starting again.
        resumed = argv[:argv.index("time.end_time_s=0.003")] + ["time.end_time_s=0.004"] + \
            argv[argv.index("time.end_time_s=0.003") + 1:] + ["--resume", "--no-bench-dem"]
        p = subprocess.run(resumed, capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with open(out) as f:
            longer = json.load(f)
        for before, after in zip(result["runs"], longer["runs"]):
            self.assertGreater(after["steps"], before["steps"])
            name = "dry" if after["depth_m"] is None else "saturated_0m"
            with open(os.path.join(tmp, "runs", name + ".log")) as f:
                log = f.read()
            self.assertEqual(log.count(bench_whole_cut.SEGMENT), 2)
            self.assertIn("resume     from", log)
            # The resumed run's wall counts both segments'.
            self.assertGreater(after["wall_s"], before["wall_s"])
        self.assertIn("saturated 0m / dry: wall", p.stdout)
        if os.path.exists(bench_dem):
            # The reduced dry scene: dashpots on one thread.
            self.assertEqual(result["bench_dem"]["benchmark"], "BM_BondedBlockCuttingViscous/1")
            self.assertGreater(result["bench_dem"]["particle_steps_per_s"], 0.0)
            self.assertAlmostEqual(dry["rate_over_bench_dem"], dry["particle_steps_per_s"] /
                                   result["bench_dem"]["particle_steps_per_s"])


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
