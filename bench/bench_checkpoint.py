#!/usr/bin/python3
"""Checkpoint cost: bytes, seconds to write one and seconds to load one.

  bench/bench_checkpoint.py [--scale paper|reduced] [--end-time S] [--repeat 3] [--coupler PATH]

Runs a stretch of the cut (the tool in the rock from the first step) to --end-time, which writes
the end-of-run checkpoint, then continues it with `coupler resume` to 1.5 times that end time.
Prints, as the median over --repeat pairs of runs:
  state [MB]       the modules' and the coupler's state in the checkpoint (array payload)
  file [MB]        the checkpoint file on disk
  write [s]        SaveState from both modules, the file written, fsync'ed and renamed
  read [s]         the file opened, read and its checksum verified
  hand back [s]    LoadState to both modules (their geometry and lists rebuilt)
  share [%]        write over the default wall-time interval (--checkpoint-every 600 s)
Target (README, "Checkpoint and restart"): write and load under 1 s each at paper scale, and
under 2 % of the wall time at the default interval.
"""
import argparse
import os
import re
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {"paper": "cases/cutting/saturated.pbtxt",
          "reduced": "cases/cutting/saturated_reduced.pbtxt"}
DEFAULT_INTERVAL_S = 600.0

WRITE = re.compile(r"checkpoint  end of run .*: (\S+), ([\d.e+-]+) MB in ([\d.e+-]+) s")
READ = re.compile(r"resume     from .*read in ([\d.e+-]+) s")
HAND_BACK = re.compile(r"resume     ([\d.e+-]+) MB of state handed back to the modules in ([\d.e+-]+) s")


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit("failed: " + " ".join(cmd) + "\n" + r.stderr[-2000:])
    return r.stderr


def one(coupler, scene, end_time, out):
    settings = ["--set", f"time.end_time_s={end_time}", "--set", "dem.tool.start_gap_m=0",
                "--set", "output.frame_interval_s=0"]
    err = run([coupler, "run", os.path.join(ROOT, scene), "--out", out] + settings)
    m = WRITE.search(err)
    if not m:
        raise SystemExit("no end-of-run checkpoint line in the run's output")
    path, state_mb, write_s = m.group(1), float(m.group(2)), float(m.group(3))
    file_mb = os.path.getsize(path if os.path.isabs(path) else os.path.join(os.getcwd(), path)) / 1e6
    err = run([coupler, "resume", out, "--set", f"time.end_time_s={1.5 * end_time}"])
    read_s = float(READ.search(err).group(1))
    hand_back_s = float(HAND_BACK.search(err).group(2))
    return {"state": state_mb, "file": file_mb, "write": write_s, "read": read_s,
            "hand back": hand_back_s}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scale", choices=sorted(SCENES), default="paper")
    ap.add_argument("--end-time", type=float, default=3e-4)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_checkpoint_") as tmp:
        for k in range(args.repeat):
            rows.append(one(args.coupler, SCENES[args.scale], args.end_time,
                            os.path.join(tmp, f"run{k}")))
    med = {key: statistics.median(r[key] for r in rows) for key in rows[0]}
    print(f"{SCENES[args.scale]} to t = {args.end_time} s, median of {args.repeat}:")
    print(f"  state {med['state']:.1f} MB, file {med['file']:.1f} MB")
    print(f"  write {med['write']:.3f} s, read {med['read']:.3f} s, hand back {med['hand back']:.3f} s")
    print(f"  share of the wall at --checkpoint-every {DEFAULT_INTERVAL_S:.0f} s: "
          f"{100 * med['write'] / DEFAULT_INTERVAL_S:.2f} %")


if __name__ == "__main__":
    main()
