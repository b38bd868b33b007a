#!/usr/bin/python3
"""rockcut sweep as a campaign: the Slurm job array it writes (--dry-run, no Slurm needed), and a
local sweep run again after an interruption, which skips the completed runs and continues the
interrupted one from its checkpoint to the result of an uninterrupted run.

  tests/python/sweep_campaign_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import signal
import subprocess
import time
import unittest

import harness  # tests/python/harness.py: the command line and CSV reading
from rockcut import slurm

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROCKCUT = os.path.join(ROOT, "scripts", "rockcut")
DRY = os.path.join(ROOT, "cases", "cutting", "dry_reduced.pbtxt")
SATURATED = os.path.join(ROOT, "cases", "cutting", "saturated_reduced.pbtxt")
ARGS = None


class JobArrayScript(unittest.TestCase):
    def test_time_limits_in_slurm_formats(self):
        self.assertEqual(slurm.parse_time_limit("90"), 5400)
        self.assertEqual(slurm.parse_time_limit("0:50"), 50)
        self.assertEqual(slurm.parse_time_limit("01:00:00"), 3600)
        self.assertEqual(slurm.parse_time_limit("2-12"), 2 * 86400 + 12 * 3600)
        with self.assertRaises(ValueError):
            slurm.parse_time_limit("an hour")
        # Warned early enough for a checkpoint and Slurm's minute of slack, at most 5 minutes.
        self.assertEqual(slurm.signal_margin_s(3600), 300)
        self.assertEqual(slurm.signal_margin_s(60), 30)

    def test_dry_run_writes_one_task_per_run_and_submits_nothing(self):
        out = os.path.join(ARGS.tmp, "campaign_dry_run")
        shutil.rmtree(out, ignore_errors=True)
        r = subprocess.run([ROCKCUT, "sweep", SATURATED, "--vary", "water_depth_m=0,2000",
                            "--seeds", "1,2", "--scheduler", "slurm", "--time", "02:00:00",
                            "--cpus-per-task", "2", "--partition", "compute", "--account", "rock",
                            "--sbatch-arg=--qos=long", "--dry-run", "--out", out,
                            "--coupler", ARGS.coupler], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("not submitted (--dry-run)", r.stdout)
        self.assertFalse(os.path.exists(os.path.join(out, slurm.JOB_ID_FILE)))
        with open(os.path.join(out, slurm.SCRIPT_FILE)) as f:
            script = f.read()
        for line in ("#SBATCH --array=0-3", "#SBATCH --time=02:00:00", "#SBATCH --cpus-per-task=2",
                     "#SBATCH --signal=B:USR1@300", "#SBATCH --requeue", "#SBATCH --partition=compute",
                     "#SBATCH --account=rock", "#SBATCH --qos=long", "scontrol requeue", "--resume"):
            self.assertIn(line, script)
        with open(os.path.join(out, slurm.TASKS_FILE)) as f:
            tasks = [line.rstrip("\n").split("\t") for line in f]
        self.assertEqual([t[0] for t in tasks],
                         ["water_depth_m=0/seed=1", "water_depth_m=2000/seed=1",
                          "water_depth_m=0/seed=2", "water_depth_m=2000/seed=2"])
        # The task's threads follow --cpus-per-task, for the DEM and the fluid.
        self.assertIn("--set dem.threads=2 --set fluid.threads=2", tasks[0][1])
        self.assertIn("--set water_depth_m=2000", tasks[1][1])
        # bash reads it.
        self.assertEqual(subprocess.run(["bash", "-n", os.path.join(out, slurm.SCRIPT_FILE)]).returncode, 0)


class LocalSweepResumes(unittest.TestCase):
    def test_a_second_run_skips_completed_runs_and_resumes_the_interrupted_one(self):
        base = os.path.join(ARGS.tmp, "campaign_resume")
        shutil.rmtree(base, ignore_errors=True)
        common = [DRY, "--vary", "dem.tool.velocity_m_s=0.5,1", "--set", "time.end_time_s=0.006",
                  "--set", "output.checkpoint_interval_s=0.0005", "--jobs", "1",
                  "--coupler", ARGS.coupler]
        straight = os.path.join(base, "straight")
        r = subprocess.run([ROCKCUT, "sweep", *common, "--out", straight], capture_output=True,
                           text=True, timeout=240)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

        out = os.path.join(base, "interrupted")
        first = os.path.join(out, "dem.tool.velocity_m_s=0.5")
        second = os.path.join(out, "dem.tool.velocity_m_s=1")
        sweep = subprocess.Popen([ROCKCUT, "sweep", *common, "--out", out],
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        # Stop the sweep (as Ctrl-C would) once the second run has written a checkpoint.
        deadline = time.time() + 120
        while time.time() < deadline and not (
                os.path.isdir(os.path.join(second, "checkpoints")) and
                any(f.endswith(".h5") for f in os.listdir(os.path.join(second, "checkpoints")))):
            time.sleep(0.02)
        sweep.send_signal(signal.SIGINT)
        sweep.communicate(timeout=60)
        with open(os.path.join(second, "summary.json")) as f:
            self.assertEqual(json.load(f)["status"], "interrupted")

        first_written = os.path.getmtime(os.path.join(first, "run.h5"))
        r = subprocess.run([ROCKCUT, "sweep", *common, "--out", out], capture_output=True,
                           text=True, timeout=240)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("1 of 2 runs completed earlier; not run again", r.stdout)
        with open(os.path.join(second, "log.txt")) as f:
            self.assertIn("resume     from", f.read())
        a = harness.read_csv(os.path.join(straight, "sweep.csv"))
        b = harness.read_csv(os.path.join(out, "sweep.csv"))
        wall = {"wall_time_s", "particle_steps_per_s", "dem_busy_s", "dem_after_reply_s"}
        for ra, rb in zip(a, b):
            for key in ra:
                # The wall-time split (coupler/session/time_split.hpp) measures the machine too.
                split = (key == "coupler_own_s" or "_phase_" in key or key.endswith("_service_s")
                         or key.endswith("_request_s"))
                if key not in wall and not split:
                    self.assertEqual(ra[key], rb[key], key)
        # The completed run was left alone.
        self.assertEqual(os.path.getmtime(os.path.join(first, "run.h5")), first_written)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
