#!/usr/bin/python3
"""rockcut status and rockcut collect on a sweep folder with a run in each state: two real runs of
a 4 ms dry cut (done), a run that failed (its log holds the error), a run still going (a process
named coupler), one whose sweep was stopped (its coupler is gone, no exit code) and one not started
(in the plan only). About 3 s.

  tests/python/status_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line and CSV reading
from rockcut import runs

ROCKCUT = os.path.join(runs.REPO, "scripts", "rockcut")
CASE = runs.case("cutting", "dry_reduced.pbtxt")
ARGS = None
NAME = "dem.tool.velocity_m_s"


class StatusAndCollect(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "status")
        shutil.rmtree(cls.out, ignore_errors=True)
        # The steady part from 1 mm, so that the short runs have forces to draw (a run that
        # stops before its steady part has none: null in summary.json).
        r = subprocess.run([ROCKCUT, "sweep", CASE, "--vary", f"{NAME}=0.5,1", "--set",
                            "time.end_time_s=0.004", "--set", "dem.tool.steady_after_m=0.001",
                            "--jobs", "2", "--out", cls.out,
                            "--coupler", ARGS.coupler], capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stdout + r.stderr
        # Four more values in the plan, as a sweep that is still going would leave them.
        with open(os.path.join(cls.out, "sweep_plan.json")) as f:
            plan = json.load(f)
        plan["values"] += ["2", "3", "4", "5"]
        with open(os.path.join(cls.out, "sweep_plan.json"), "w") as f:
            json.dump(plan, f)

        def run_folder(value, record, log):
            d = os.path.join(cls.out, f"{NAME}={value}")
            os.makedirs(d)
            with open(os.path.join(d, "sweep_run.json"), "w") as f:
                json.dump(record, f)
            with open(os.path.join(d, "log.txt"), "w") as f:
                f.write(log)

        run_folder("2", {"command": [], "exit_code": 2},
                   "$ coupler run ...\nscene.pbtxt:3:5: time.dt_s = -1 is out of range\n")
        # A process whose command line names a coupler, as a running run's does.
        fake = os.path.join(ARGS.tmp, "status_bin", "coupler")
        os.makedirs(os.path.dirname(fake), exist_ok=True)
        if not os.path.exists(fake):
            os.symlink(shutil.which("sleep"), fake)
        cls.running = subprocess.Popen([fake, "60"])
        run_folder("3", {"command": [], "pid": cls.running.pid},
                   "t = 0.001 / 0.004 s  step 100 / 400  wall 1.0 s  ETA 3.0 s\n"
                   "t = 0.002 / 0.004 s  step 200 / 400  wall 2.0 s  ETA 2.0 s\n")
        gone = subprocess.Popen(["true"])
        gone.wait()
        run_folder("4", {"command": [], "pid": gone.pid},
                   "t = 0.001 / 0.004 s  step 100 / 400  wall 1.0 s  ETA 3.0 s\n")

    @classmethod
    def tearDownClass(cls):
        cls.running.kill()
        cls.running.wait()

    def test_status_names_each_runs_state(self):
        r = subprocess.run([ROCKCUT, "status", self.out], capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        lines = {l.split()[0]: l for l in r.stdout.splitlines() if l.startswith(NAME)}
        self.assertEqual(sorted(lines), [f"{NAME}={v}" for v in ("0.5", "1", "2", "3", "4", "5")])
        self.assertRegex(lines[f"{NAME}=0.5"], r"done +[0-9.]+ s wall")
        self.assertIn("failed", lines[f"{NAME}=2"])
        self.assertIn("exit code 2: scene.pbtxt:3:5: time.dt_s = -1 is out of range",
                      lines[f"{NAME}=2"])
        self.assertIn("running", lines[f"{NAME}=3"])
        self.assertIn("t = 0.002 / 0.004 s, 50 % of the steps, ETA 2 s", lines[f"{NAME}=3"])
        self.assertIn("interrupted", lines[f"{NAME}=4"])
        self.assertIn("pending", lines[f"{NAME}=5"])
        self.assertIn("2 done, 1 failed, 1 running, 1 interrupted, 1 pending", r.stdout)

    def test_collect_draws_the_finished_runs_and_names_the_missing(self):
        r = subprocess.run([ROCKCUT, "collect", self.out], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        for value, state in (("2", "failed"), ("3", "running"), ("4", "interrupted"),
                             ("5", "pending")):
            self.assertIn(f"missing: {NAME}={value} ({state}", r.stderr)
        self.assertIn("collected 2 of 6 runs; missing 4", r.stdout)
        rows = harness.read_csv(os.path.join(self.out, "sweep.csv"))
        done = [row for row in rows if row.get("status") == "completed"]
        self.assertEqual([row[NAME] for row in done], ["0.5", "1"])
        self.assertTrue(os.path.isfile(os.path.join(self.out, "fig08_forces.png")))

    def test_a_folder_that_is_no_sweep_is_refused(self):
        empty = os.path.join(ARGS.tmp, "status_empty")
        os.makedirs(empty, exist_ok=True)
        r = subprocess.run([ROCKCUT, "status", empty], capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 2)
        self.assertIn("cannot tell the varied parameter", r.stderr)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
