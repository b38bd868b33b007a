#!/usr/bin/python3
"""A small sweep run locally and through Slurm: the scheduler's overhead on the wall time.

  bench/bench_campaign.py [--end-time 0.02] [--coupler PATH]

Runs the same sweep (cases/cutting/saturated_reduced.pbtxt, water_depth_m = 0, 2000 x seeds 1, 2,
one thread each) twice: `rockcut sweep --jobs 2` on this machine, and `rockcut sweep --scheduler
slurm --cpus-per-task 1` on a single-node Slurm started for the purpose (tests/slurm/
slurm_cluster.py: root only), with a time limit no run reaches. Prints both wall times (from the
command to the last run's end) and Slurm's overhead. Target (README, "On a cluster"): under 5 %.
"""
import argparse
import importlib.util
import os
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROCKCUT = os.path.join(ROOT, "scripts", "rockcut")
CASE = os.path.join(ROOT, "cases", "cutting", "saturated_reduced.pbtxt")


def load_cluster_module():
    spec = importlib.util.spec_from_file_location(
        "slurm_cluster", os.path.join(ROOT, "tests", "slurm", "slurm_cluster.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--end-time", type=float, default=0.02)
    ap.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    a = ap.parse_args()
    common = [CASE, "--vary", "water_depth_m=0,2000", "--seeds", "1,2", "--coupler", a.coupler,
              "--set", f"time.end_time_s={a.end_time}"]
    with tempfile.TemporaryDirectory(prefix="bench_campaign_") as tmp:
        os.chmod(tmp, 0o755)  # munged runs as the munge user, who must reach its socket
        env = dict(os.environ)
        t0 = time.monotonic()
        subprocess.run([ROCKCUT, "sweep"] + common + ["--set", "dem.threads=1", "--set",
                                                      "fluid.threads=1", "--jobs", "2", "--out",
                                                      os.path.join(tmp, "local")],
                       env=env, check=True, capture_output=True)
        local_s = time.monotonic() - t0
        with load_cluster_module().SlurmCluster(os.path.join(tmp, "cluster")) as cluster:
            out = os.path.join(tmp, "slurm")
            t0 = time.monotonic()
            subprocess.run([ROCKCUT, "sweep"] + common + ["--scheduler", "slurm", "--time",
                                                          "00:30:00", "--cpus-per-task", "1",
                                                          "--out", out],
                           env=cluster.env, check=True, capture_output=True)
            with open(os.path.join(out, "slurm_job_id")) as f:
                job = f.read().strip()
            while subprocess.run(["squeue", "-h", "-r", "-j", job], env=cluster.env,
                                 capture_output=True, text=True).stdout.strip():
                time.sleep(0.2)
            slurm_s = time.monotonic() - t0
    print(f"4 runs to t = {a.end_time} s, 2 at a time: local {local_s:.1f} s, "
          f"Slurm {slurm_s:.1f} s, overhead {100 * (slurm_s - local_s) / local_s:+.1f} %")


if __name__ == "__main__":
    main()
