#!/usr/bin/python3
"""Coupled cutting step: wall time over ipc and inproc, and where it goes.

  bench/bench_coupled.py [--scale reduced|paper|both] [--repeat 3] [--coupler PATH]
                         [--set PATH=VALUE ...]

Runs cases/cutting/saturated_reduced.pbtxt (647 discs) and cases/cutting/saturated.pbtxt (55,177
discs) for a short stretch of the cut (the tool in the rock) with each transport and prints, per
run, the median over --repeat runs of:
  wall [s]           the coupler's loop (summary.json wall_time_s)
  p-steps/s          particle-steps per second of the coupled run
  dem, fluid [%]     each module's own handling time (Envelope.busy_s) as a share of the wall time
  dem ovl [%]        the part of the DEM's share spent after its replies (Envelope.after_reply_s):
                     its contact forces, computed while the fluid steps
  rest [%]           wall - dem - fluid: transport, the coupler's output and waiting (negative when
                     the fluid's work hides behind the DEM's contact forces, which overlap it)
  fl/step            the fluid's busy time per exchange in units of the rest of the wall per DEM
                     step, c = N fluid / (1 - fluid) (see fluid_cost_in_dem_steps)
and the ratio of the ipc to the inproc wall time. Targets (issue 5): ipc / inproc <= 1.10, fluid
<= 20 % of the coupled wall time at the coupler's N. For the fluid target each scale also prints
the smallest N that meets it and how much faster the fluid's step would have to be at this N.
--set overrides a scene field in every run after the stretch's own settings, e.g.
`--set coupling.interval=10` for the share at another N.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# A stretch of the cut with the tool starting at the block (start_gap 0), so contacts, breaks and
# pressures are active from the first step. Frames off: output is not what is measured. The
# reduced scene runs 10 mm of cut on one thread (the scene's), the paper-scale one 0.3 mm on two.
SCALES = {
    "reduced": ("cases/cutting/saturated_reduced.pbtxt",
                ["time.end_time_s=0.01", "output.frame_interval_s=0", "dem.tool.start_gap_m=0"]),
    "paper": ("cases/cutting/saturated.pbtxt",
              ["time.end_time_s=0.0003", "output.frame_interval_s=0", "dem.tool.start_gap_m=0",
               "output.timeseries_every_steps=2000"]),
}


def _odds(share):
    """share / (1 - share): a fluid of cost c at interval N has share s where c = N _odds(s)."""
    return share / (1.0 - share)


def fluid_cost_in_dem_steps(interval, fluid_share):
    """The fluid's cost per exchange, c, in units of the rest of the wall per DEM step.

    An exchange covers N DEM steps. If the wall per exchange is N d (the DEM, transport and
    coupler: everything but the fluid's busy time) plus c d (the fluid's busy time), the fluid's
    share is s = c / (N + c), so c = N s / (1 - s). c measures the fluid's step against the DEM's
    independently of N: the measured shares at N = 3, 5, 7 and 10 (bench/README.md) all give
    c = 2.3-2.4 inproc.
    """
    if not 0 <= fluid_share < 1:
        raise ValueError("fluid share %r is not in [0, 1)" % fluid_share)
    return interval * _odds(fluid_share)


def interval_for_fluid_share(cost, share=0.2):
    """The smallest whole N at which a fluid of cost c (DEM steps per exchange) is at most share
    of the wall: c / (N + c) <= share, i.e. N >= c (1 - share) / share (4 c for 20 %)."""
    return max(1, math.ceil(cost / _odds(share) - 1e-9))


def fluid_speedup_for_share(cost, interval, share=0.2):
    """How many times faster the fluid's step must be for its share to be at most share at this
    N: the cost must fall to N share / (1 - share) (N / 4 for 20 %). Below 1 it already is."""
    return cost / (interval * _odds(share))


def run(coupler, scene, sets, transport):
    with tempfile.TemporaryDirectory(prefix="rockcut-bench-") as out:
        argv = [coupler, "run", os.path.join(ROOT, scene), "--out", out, "--transport", transport]
        for s in sets:
            argv += ["--set", s]
        p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            sys.exit("bench_coupled: %s failed (%d):\n%s" % (" ".join(argv), p.returncode, p.stderr))
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scale", choices=["reduced", "paper", "both"], default="both")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--coupler", default=os.path.join(ROOT, "build", "bin", "coupler"))
    ap.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                    help="scene override for every run (repeatable)")
    args = ap.parse_args()
    scales = ["reduced", "paper"] if args.scale == "both" else [args.scale]
    print("%-8s %-7s %6s %5s %9s %9s %7s %8s %7s %7s %7s" %
          ("scale", "trans", "parts", "N", "wall_s", "p-steps/s", "dem%", "dem_ovl%", "fluid%",
           "rest%", "fl/step"))
    for scale in scales:
        scene, stretch = SCALES[scale]
        sets = stretch + args.set
        walls = {}
        costs = {}
        for transport in ["inproc", "ipc"]:
            rows = [run(args.coupler, scene, sets, transport) for _ in range(args.repeat)]
            wall = statistics.median(r["wall_time_s"] for r in rows)
            dem = statistics.median(r["dem_busy_s"] / r["wall_time_s"] for r in rows)
            ovl = statistics.median(r["dem_after_reply_s"] / r["wall_time_s"] for r in rows)
            fluid = statistics.median(r["fluid_busy_s"] / r["wall_time_s"] for r in rows)
            rate = statistics.median(r["particle_steps_per_s"] for r in rows)
            walls[transport] = wall
            r = rows[0]
            interval = r["coupling_interval"]
            costs[transport] = fluid_cost_in_dem_steps(interval, fluid)
            print("%-8s %-7s %6d %5d %9.3f %9.3g %6.1f%% %7.1f%% %6.1f%% %6.1f%% %7.2f" %
                  (scale, transport, r["particles"], interval, wall, rate,
                   100 * dem, 100 * ovl, 100 * fluid, 100 * (1 - dem - fluid),
                   costs[transport]))
        print("%-8s ipc / inproc wall time: %.3f (target <= 1.10)" %
              (scale, walls["ipc"] / walls["inproc"]))
        for transport in ["inproc", "ipc"]:
            c = costs[transport]
            print("%-8s %s: fluid <= 20 %% needs N >= %d, or at N = %d a fluid step %.2f times "
                  "as fast" % (scale, transport, interval_for_fluid_share(c), interval,
                               fluid_speedup_for_share(c, interval)))


if __name__ == "__main__":
    main()
