"""rockcut calibrate --target on Slurm against a real single-node Slurm (munged, slurmctld and
slurmd started by this test, tests/slurm/slurm_cluster.py): each round's UCS and Brazilian runs go
as two job arrays, and the calibration waits for them. The rounds must equal those of the same
calibration run here, value for value: the scheduler changes where the runs go, not what they give.
Then `rockcut envelope` on Slurm, its fit equal to the local one's.

  slurm_calibrate_test.py --coupler PATH --tmp DIR      (ctest; exit 77 = skipped, with the reason)

The coarse discs keep each run to a few seconds; the runs are far inside their one-minute limit.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)  # the test's own helper, not the package
from slurm_cluster import SlurmCluster, Unavailable  # noqa: E402

SKIPPED = 77
ROCKCUT = os.path.join(ROOT, "scripts", "rockcut")
COARSE = os.path.join(ROOT, "cases", "rock", "default_rock_coarse.pbtxt")
CALIBRATE = ["calibrate", "--target", "ucs=20MPa,E=6.5GPa,nu=0.28", "--rock", COARSE,
             "--seeds", "1,2", "--tolerance", "0.05"]
ENVELOPE = ["envelope", "--rock", COARSE, "--seeds", "1", "--confining-mpa", "1,2"]


def rockcut(args, env):
    r = subprocess.run([ROCKCUT] + args, env=env, capture_output=True, text=True)
    print("$ rockcut " + " ".join(args) + "\n" + r.stdout + r.stderr, flush=True)
    return r


def read(path):
    with open(path) as f:
        return f.read()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--coupler", required=True)
    p.add_argument("--tmp", required=True)
    a = p.parse_args()
    tmp = os.path.join(a.tmp, "slurm_calibrate")
    shutil.rmtree(tmp, ignore_errors=True)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"), ROCKCUT_COUPLER=a.coupler)
    slurm = ["--scheduler", "slurm", "--time", "1"]
    try:
        with SlurmCluster(os.path.join(tmp, "cluster")) as cluster:
            cenv = dict(cluster.env, PYTHONPATH=env["PYTHONPATH"], ROCKCUT_COUPLER=a.coupler)
            r = rockcut(CALIBRATE + slurm + ["--out", os.path.join(tmp, "cal_slurm")], cenv)
            assert r.returncode == 0, "the calibration on Slurm did not converge or failed"
            assert "as Slurm job" in r.stdout, "no job array was submitted"
            r = rockcut(ENVELOPE + slurm + [os.path.join(tmp, "env_slurm")], cenv)
            assert r.returncode == 0, "the envelope on Slurm failed"
    except Unavailable as e:
        print(f"SKIPPED: {e}")
        return SKIPPED
    r = rockcut(CALIBRATE + ["--jobs", "2", "--out", os.path.join(tmp, "cal_local")], env)
    assert r.returncode == 0, "the local calibration failed"
    r = rockcut(ENVELOPE + ["--jobs", "2", os.path.join(tmp, "env_local")], env)
    assert r.returncode == 0, "the local envelope failed"

    on_slurm = read(os.path.join(tmp, "cal_slurm", "calibration_rounds.csv"))
    here = read(os.path.join(tmp, "cal_local", "calibration_rounds.csv"))
    assert on_slurm == here, f"the rounds differ:\n{on_slurm}\n{here}"
    fits = [json.load(open(os.path.join(tmp, d, "envelope.json")))["peak"]
            for d in ("env_slurm", "env_local")]
    assert fits[0] == fits[1], f"the envelopes differ: {fits}"
    print(f"calibration_rounds.csv ({on_slurm.count(chr(10)) - 1} rounds) and the peak envelope "
          "equal on Slurm and here")
    return 0


if __name__ == "__main__":
    sys.exit(main())
