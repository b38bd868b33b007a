"""Means of a cutting run's time series over windows of tool travel.

  rockcut windows OUT [OUT ...] [--every-mm 10] [--from-mm 0] [--csv FILE] [--plot PNG]
                  [--plot-travel PNG] [--frames]

OUT is a run's output folder (`coupler run ... --out OUT`), or its run.h5, also of a run still
going. A paper-scale cut takes hours, and one stopped early (Ctrl-C) or cut short
(`--set time.end_time_s=...`) may not reach the steady part from which summary.json takes its means. The window means show how far the force has
settled. For each window [a, a + every) of `tool_travel_m`, from --from-mm to the last sample, this
prints one row:

  travel [mm]              the window; the last one ends at the last sample (a remainder under
                           1 % of a window joins the window before it)
  samples                  time-series samples in it
  Fh, Fv [kN/m]            mean horizontal force resisting the cut (-tool_force_x) and vertical
                           force on the tool (up > 0): the signs of summary.json
  Fh peak [kN/m]           the largest horizontal force resisting the cut in the window: what
                           a dynamic cut's force is read by (summary.json's
                           force_horizontal_peak_n_per_m over its steady part)
  contact %                the share of the window's samples with a force on the tool
                           (summary.json's tool_contact_fraction): a dynamic cut's mean is
                           mostly the zeros between chips
  P1, P2, P3 [MPa]         coupled runs: mean p - p_hydro of each pressure node, over the samples
                           in which the node held a particle centre (as summary.json); '-' if none
  tensile, shear, shear %  bond breaks by mode at the window's last sample
  chips, chip mm^2         chips and their mean area at the window's last sample
  cavitated                coupled runs: particles at the cavitation limit at the last sample
  window breaks            bonds broken within the window (run.h5's /breaks, by the tool travel at
                           the time of each break)
  ahead [mm], below tip %  where they broke: the median distance of the breaks ahead of the tool
                           tip in the cutting direction at the time of each break (negative:
                           behind it) and the share of them below the tip's height. A crushed zone
                           that grows ahead of and under the tool shows as both growing. The
                           coupler writes /breaks with each frame, so in a run still going the
                           windows past its newest frame show '-' here.

Under each table one line fits the horizontal force of the steady part (tool travel from
summary.json's steady_after_m, or while the run has no summary.json the scene's
dem.tool.steady_after_m, two cutting depths by default): its mean and its least-squares slope
against travel in kN/m per mm, how far a cut still climbs where summary.json takes its mean.

The means are those of summary.json taken over a window instead of the steady part: with
--from-mm at `steady_after_m` and --every-mm past the end, the one window gives summary.json's
force_*_mean_n_per_m, force_horizontal_peak_n_per_m, tool_contact_fraction and
pressure_*_mean_pa (tests/python/windows_test.py).

  --every-mm W   window width in mm of tool travel (default 10)
  --from-mm A    first window's start in mm (default 0: the tool at the block)
  --csv FILE     also write the rows as CSV (SI units, one column per value; `run` names the
                 run, `water_depth_m` and `seed` are its scene's depth and specimen seed)
  --plot PNG     draw the window means of the runs against their hydrostatic pressure
                 (summary.json's hydrostatic_pressure_pa; a run without summary.json, still
                 going, is left out with a note), one line per window of full width: Fh, Fv,
                 the shear fraction, the mean chip area, P1-P3 and the cavitated particles.
                 Several runs at one depth (other seeds) are drawn as their mean, a bar from
                 their lowest to their highest value and each run as a faint dot, as
                 rockcut sweep draws its seeds. A window shorter than --every-mm (a run's
                 last) is not drawn: for one point per run over the steady part, give its
                 start and length (a paper-scale cut: --from-mm 40 --every-mm 59).
  --plot-travel PNG
                 draw the window means of each run against tool travel, one line per run
                 (labelled with its depth and seed), in the same panels as --plot: whole cuts
                 at several depths side by side, how far each has settled, and where its chips
                 came off (--every-mm 1 for a fine trace). Also for a run still going.

  --frames       also table what lies on the tool in each frame of run.h5 (frames need the
                 `position`, `radius` and `damage` fields): the discs whose centre lies above the
                 block's initial top surface (the cut material, count and area), and of them the
                 ones from 40 mm behind the tip to 10 mm ahead of it (the pile the tool pushes),
                 and the loose discs there (damage 1: every bond broken) above the tip's height.
                 A cut whose crushed grains pile up on the tool shows a growing loose count.

Several OUTs give one table each, in the order given: runs of one scene at several depths stopped
at the same travel (paper-scale cuts take hours each) are compared window by window, the way
docs/record/results_local_damping.md compares its paper-scale runs.

Exit status: 0 on success, 2 on bad arguments or a file without a cutting time series.
"""
import argparse
import csv
import math
import os

# The jobs of the verb, one module each; their names are also reached from here (tests, users).
from .window_figures import depth_points, plot, plot_travel, travel_lines, window_panels  # noqa: F401
from .window_means import (Run, fail, print_table, print_trend, read_breaks,  # noqa: F401
                           read_series, run_facts, steady_start, steady_trend, windows)
from .window_pile import pile_rows, print_pile  # noqa: F401


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut windows", description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="+", help="a run's output folder, or its run.h5")
    ap.add_argument("--every-mm", type=float, default=10.0)
    ap.add_argument("--from-mm", type=float, default=0.0)
    ap.add_argument("--csv", help="also write the rows to this CSV file (SI units)")
    ap.add_argument("--plot", help="draw the runs' window means against p_hydro into this PNG")
    ap.add_argument("--plot-travel", help="draw each run's window means against tool travel "
                    "into this PNG")
    ap.add_argument("--frames", action="store_true",
                    help="also table what lies on the tool in each frame")
    args = ap.parse_args(argv)
    if not (args.every_mm > 0) or not math.isfinite(args.every_mm):
        fail(f"--every-mm {args.every_mm}: must be a window width > 0 mm")
    if not math.isfinite(args.from_mm):
        fail(f"--from-mm {args.from_mm}: must be a number of mm")
    for option, target in (("--csv", args.csv), ("--plot", args.plot),
                           ("--plot-travel", args.plot_travel)):
        folder = os.path.dirname(os.path.abspath(target)) if target else None
        if folder and not os.path.isdir(folder):
            fail(f"{option} {target}: no folder {folder} to write it in")
    runs = []
    for out in args.out:
        path, series = read_series(out)
        rows = windows(series, args.every_mm * 1e-3, args.from_mm * 1e-3, read_breaks(path))
        reached_mm = float(series["tool_travel_m"].max()) * 1e3
        if not rows:
            fail(f"{path}: no sample at or beyond {args.from_mm} mm of travel "
                 f"(the run reached {reached_mm:.2f} mm)")
        depth, seed, p_hydro = run_facts(path)
        runs.append(Run(path, depth, seed, p_hydro, rows))
        if len(runs) > 1:
            print()
        print(f"{path}: {len(series['tool_travel_m'])} samples, tool travel up to "
              f"{reached_mm:.2f} mm, water depth {depth:g} m, seed {seed}")
        print_table(rows)
        steady_m = steady_start(path)
        print_trend(steady_trend(series, steady_m), steady_m, reached_mm * 1e-3)
        if args.frames:
            print()
            print_pile(pile_rows(path, series))
    if args.plot and not depth_points(runs, args.every_mm * 1e-3, lambda w: w["fh_n_per_m"]):
        reached = ", ".join(f"{r.rows[-1]['to_m'] * 1e3:.2f}" for r in runs)
        fail(f"--plot {args.plot}: no window of full width ({args.every_mm:g} mm from "
             f"{args.from_mm:g} mm) in a run with a summary.json to draw (the runs reached "
             f"{reached} mm; a shorter last window is not drawn): give a smaller --every-mm, "
             f"e.g. the steady part's length for one point per run")
    if args.csv:
        first = ["run", "water_depth_m", "seed"]
        table = [{"run": r.label, "water_depth_m": r.depth, "seed": r.seed, **row}
                 for r in runs for row in r.rows]
        keys = first + sorted({k for r in table for k in r} - set(first))
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=keys)
            writer.writeheader()
            writer.writerows(table)
    if args.plot:
        plot(runs, args.every_mm * 1e-3, args.plot)
        print(f"plot: {args.plot}")
    if args.plot_travel:
        plot_travel(runs, args.every_mm * 1e-3, args.plot_travel)
        print(f"plot: {args.plot_travel}")
    return 0
