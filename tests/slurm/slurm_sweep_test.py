"""The water-depth sweep as a Slurm job array against a real single-node Slurm (munged, slurmctld
and slurmd started by this test, tests/slurm/slurm_cluster.py): 2 depths of a short reduced
saturated cut, one task per CPU of the node, each with a time limit shorter than its run, so that
tasks are warned (USR1), checkpoint, requeue and resume. (The array's tasks for values times seeds
are checked without Slurm by tests/python/sweep_campaign_test.py; a third task here would only
wait for a CPU and double the test's minutes.) The collected sweep.csv must equal the same sweep run
locally, value for value (the wall-time columns aside).

  slurm_sweep_test.py --coupler PATH --tmp DIR      (ctest; exit 77 = skipped, with the reason)

Timing: Slurm's time limits are whole minutes, so each task gets one minute and the warning 25 s
before it; slurmctld checks time limits every 30 s and warns a task that will be within its margin
by the next check, so a task is warned 5-35 s after it starts, and a run of this cut (its fluid
stepped with every DEM step, coupling.interval 1) takes 30-45 s on one core of this 2-core machine.
A requeued task starts again 12 s after its requeue (the cluster's cred_expire and sched_interval,
slurm_cluster.py).
"""
import argparse
import csv
import glob
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)  # the test's own helper, not the package
from slurm_cluster import SlurmCluster, Unavailable  # noqa: E402

SKIPPED = 77
# A sweep in which no task's log grows and the queue does not change for this long has stalled.
STALL_S = 300
ROCKCUT = os.path.join(ROOT, "scripts", "rockcut")
CASE = os.path.join(ROOT, "cases", "cutting", "saturated_reduced.pbtxt")
# Summary values that measure the machine, not the run.
WALL = {"wall_time_s", "particle_steps_per_s", "dem_busy_s", "dem_after_reply_s", "fluid_busy_s",
        "fluid_after_reply_s"}


def is_time_split(key):
    """The wall-time split of summary.json (coupler/session/time_split.hpp): the machine's."""
    return (key == "coupler_own_s" or "_phase_" in key or key.endswith("_service_s")
            or key.endswith("_request_s"))


def rockcut(args, env):
    r = subprocess.run([ROCKCUT] + args, env=env, capture_output=True, text=True)
    print("$ rockcut " + " ".join(args) + "\n" + r.stdout + r.stderr, flush=True)
    return r


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--coupler", required=True)
    p.add_argument("--tmp", required=True)
    a = p.parse_args()
    tmp = os.path.join(a.tmp, "slurm_sweep")
    shutil.rmtree(tmp, ignore_errors=True)
    common = [CASE, "--vary", "water_depth_m=0,2000", "--seeds", "2", "--coupler", a.coupler,
              "--set", "time.end_time_s=0.035", "--set", "output.frame_interval_s=0.01",
              "--set", "coupling.interval=1"]
    try:
        with SlurmCluster(os.path.join(tmp, "cluster")) as cluster:
            env = dict(cluster.env)
            env["PYTHONPATH"] = os.path.join(ROOT, "python")
            sdir = os.path.join(tmp, "on_slurm")
            r = rockcut(["sweep"] + common + ["--scheduler", "slurm", "--time", "1",
                                              "--cpus-per-task", "1",
                                              "--sbatch-arg=--signal=B:USR1@25", "--out", sdir],
                        env)
            assert r.returncode == 0, "the submission failed"
            with open(os.path.join(sdir, "slurm_job_id")) as f:
                job = f.read().strip()
            # Wait on progress, not on a fixed wall: a busy machine slows every task, but each
            # task's log grows as its run advances (the progress line, a checkpoint, a requeue,
            # a resume), and the queue changes as tasks start and end. Only a sweep in which
            # nothing moves for STALL_S fails.
            last_change, last_seen = time.time(), None
            while True:
                q = subprocess.run(["squeue", "-h", "-r", "-j", job, "-o", "%i %T"], env=env,
                                   capture_output=True, text=True)
                if q.returncode == 0 and not q.stdout.strip():
                    break
                seen = (q.stdout, tuple(sorted(
                    (f, os.path.getsize(f)) for f in glob.glob(os.path.join(sdir, "*", "*", "log.txt")))))
                if seen != last_seen:
                    last_change, last_seen = time.time(), seen
                elif time.time() - last_change > STALL_S:
                    rockcut(["status", sdir], env)
                    raise AssertionError(f"the job array made no progress for {STALL_S} s:\n" +
                                         cluster.log_tail())
                time.sleep(3)
            rockcut(["status", sdir], env)
            r = rockcut(["collect", sdir], env)
            assert r.returncode == 0, "collect failed"
            resumed = [f for f in glob.glob(os.path.join(sdir, "*", "*", "log.txt"))
                       if "resume     from" in open(f, errors="replace").read()]
            print(f"{len(resumed)} of 2 runs were requeued at their time limit and resumed")
            assert resumed, "no task reached its time limit: nothing was checkpointed and resumed"
        # The same sweep here, with the tasks' thread counts, after the array (run beside it, the
        # two competed for the cores and slowed the tasks towards their time limits).
        ldir = os.path.join(tmp, "local")
        local_env = dict(os.environ)
        local_env["PYTHONPATH"] = os.path.join(ROOT, "python")
        local = subprocess.run(
            [ROCKCUT, "sweep"] + common + ["--set", "dem.threads=1", "--set", "fluid.threads=1",
                                           "--jobs", "2", "--out", ldir],
            env=local_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        print("$ rockcut sweep ... --jobs 2 (locally)\n" + local.stdout)
        assert local.returncode == 0, "the local sweep failed"
    except Unavailable as e:
        print(f"SKIPPED: {e}")
        return SKIPPED

    slurm_rows, local_rows = read_csv(os.path.join(sdir, "sweep.csv")), \
        read_csv(os.path.join(ldir, "sweep.csv"))
    assert len(slurm_rows) == len(local_rows) == 2
    assert set(slurm_rows[0]) == set(local_rows[0]), \
        f"columns differ: {set(slurm_rows[0]) ^ set(local_rows[0])}"
    compared = 0
    for s, l in zip(slurm_rows, local_rows):
        for key in s:
            if key in WALL or is_time_split(key):
                continue
            assert s[key] == l[key], \
                f"{key} differs at depth {s['water_depth_m']} seed {s['seed']}: {s[key]} vs {l[key]}"
            compared += 1
    print(f"sweep.csv: {compared} values equal on Slurm and locally")
    return 0


if __name__ == "__main__":
    sys.exit(main())
