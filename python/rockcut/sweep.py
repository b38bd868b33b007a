"""Parameter sweep of a scene, and the paper's figures 8-12 from it.

  rockcut sweep CASE --vary water_depth_m=0,10,40,100,250,1000,2000 [--seeds 1,2,3] [--jobs N]
                [--out DIR] [--set path=value ...] [--coupler PATH] [--plot-only]
  rockcut sweep CASE --vary ... [--seeds ...] --scheduler slurm [--partition P] [--time HH:MM:SS]
                [--cpus-per-task C] [--account A] [--sbatch-arg ARG ...] [--dry-run] --out DIR
  rockcut sweep --status DIR      (rockcut status DIR)
  rockcut sweep --collect DIR     (rockcut collect DIR)

Runs `coupler run CASE --out DIR/<name>=<value> [--set path=value ...] --set <name>=<value>` once
per value, --jobs at a time, each run's output in DIR/<name>=<value>/log.txt, and prints one line
per finished run. With --seeds, every value is run once per specimen seed
(`--set dem.specimen.seed=S`) into DIR/<name>=<value>/seed=<S>/, seed by seed, so that an
interrupted sweep already holds whole curves. Then writes
  DIR/sweep.csv                one row per run: the varied parameter, hydrostatic_pressure_pa,
                               (seed,) then every scalar key of the runs' summary.json (sorted)
                               and the run's exit_code
  DIR/sweep_mean.csv           with --seeds: one row per value, the mean, min and max over the
                               seeds of every numeric key (key, key_min, key_max) and runs_ok
  DIR/fig08_forces.png         mean horizontal and vertical tool force against the hydrostatic
                               pressure (paper figure 8)
  DIR/fig09_pressure_p1.png    mean pore pressure at P1 (figure 9)
  DIR/fig10_pressure_p2_p3.png mean pore pressures at P2 and P3 (figure 10)
  DIR/fig11_damage_<v>.png     damage of the last frame of the smallest value (figure 11: 0 m)
  DIR/fig12_damage_<v>.png     ... and of the largest value (figure 12: 2000 m)
  DIR/breaks_fraction.png      tensile and shear share of the broken bonds
  DIR/chips.png                number of chips and their mean area
When the varied parameter is not water_depth_m, figures 8-10 are drawn against the varied value.
With --seeds the figures draw the mean over the seeds, a bar over their range and each seed's run
as a faint dot; the damage maps are those of the first seed.
A figure whose summary keys no run has (e.g. the pressures of a dry scene) is skipped with a note.

  --out DIR      default out/sweep_<case stem>
  --jobs N       runs at a time; default the CPUs divided by the scene's dem.threads
  --coupler PATH default build/bin/coupler of this repository
  --seeds LIST   specimen seeds, e.g. 1,2,3: one run per value and seed (default: the scene's seed)
  --plot-only    run nothing: collect sweep.csv and draw from DIR (CASE, --vary and --seeds may then
                 be left out when --out is given: they are found from DIR's <name>=<value> and
                 seed=<S> folders)

Re-running the same sweep skips the runs that have completed and continues the interrupted ones
from their checkpoints (`coupler run --resume`, README "Checkpoint and restart"); a run whose
command changed (another --set) starts afresh.

On a cluster (--scheduler slurm) the sweep writes DIR/job.sbatch, a job array with one task per
run (value x seed) listed in DIR/tasks.tsv, readable and editable, submits it with sbatch (not with
--dry-run) and prints the job id and how to follow it. Each task asks for USR1 before its time
limit, checkpoints, requeues itself and resumes: runs longer than the partition's limit complete,
with the results of uninterrupted runs. The DEM and fluid threads of a task are --cpus-per-task
(default the scene's dem.threads). Re-running the command while the job is queued prints the state
and collects what has finished; once the job has left the queue it resubmits the runs that have
not completed.

Exit status: 0 if every run succeeded (coupler exit code 0), 1 if any failed (the sweep goes on and
draws what it has), 2 on bad arguments, 130 if interrupted. With --plot-only: 0 once drawn (failed
runs are listed in a note), 1 if DIR holds no run results.
"""
import argparse
import os
import sys

from . import campaign, runs, slurm
from .campaign import parse_seeds
from .collect import collect_campaign, tables_and_figures
from .status import print_status
from .sweep_local import run_sweep
from .sweep_slurm import submit_sweep

PLAN = campaign.PLAN  # in the sweep folder: the runs a sweep will make (campaign.py)


# ---------------------------------------------------------------------------------------------
# Arguments


def parse_vary(text):
    """'name=v1,v2,...' -> (name, [v1, v2, ...]) with the values kept as typed (they name the
    run folders)."""
    name, sep, values = text.partition("=")
    values = [v.strip() for v in values.split(",") if v.strip()]
    if not sep or not name or not values:
        raise argparse.ArgumentTypeError(f"expected name=v1,v2,... , got '{text}'")
    if len(set(values)) != len(values):
        raise argparse.ArgumentTypeError(f"repeated value in '{text}'")
    return name.strip(), values


def parse_args(argv):
    p = argparse.ArgumentParser(prog="rockcut sweep", description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n".join(__doc__.split("\n")[1:]))
    p.add_argument("case", nargs="?", help="scene file (protobuf text format)")
    p.add_argument("--vary", type=parse_vary, help="name=v1,v2,... : the scene field to vary")
    p.add_argument("--seeds", type=parse_seeds, help="1,2,3 : one run per value and specimen seed")
    p.add_argument("--jobs", type=int, help="runs at a time")
    p.add_argument("--out", help="sweep directory (default out/sweep_<case stem>)")
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                   help="scene override passed to every run (repeatable)")
    p.add_argument("--coupler", help="the coupler to run (default build/bin/coupler)")
    p.add_argument("--plot-only", action="store_true", help="run nothing, collect and draw")
    p.add_argument("--status", metavar="DIR", help="the state of each run of sweep folder DIR")
    p.add_argument("--collect", metavar="DIR", help="sweep.csv and figures from DIR's finished runs")
    cluster = p.add_argument_group("on a cluster")
    cluster.add_argument("--scheduler", choices=["local", "slurm"], default="local",
                         help="local: runs here, --jobs at a time (default); slurm: a job array")
    cluster.add_argument("--partition", help="Slurm partition")
    cluster.add_argument("--time", default="01:00:00",
                         help="time limit of each task (Slurm format, default 01:00:00); a run "
                              "longer than it checkpoints, requeues and resumes")
    cluster.add_argument("--cpus-per-task", type=int, help="CPUs of each task (default the "
                         "scene's dem.threads); the DEM and the fluid use them all")
    cluster.add_argument("--account", help="Slurm account")
    cluster.add_argument("--sbatch-arg", action="append", default=[], metavar="ARG",
                         help="an extra #SBATCH line, e.g. --sbatch-arg=--qos=long (repeatable)")
    cluster.add_argument("--dry-run", action="store_true",
                         help="write DIR/job.sbatch and DIR/tasks.tsv, submit nothing")
    if argv and argv[0] in ("--status", "--collect") and len(argv) == 2:
        return argparse.Namespace(status=argv[1] if argv[0] == "--status" else None,
                                  collect=argv[1] if argv[0] == "--collect" else None)
    args = p.parse_args(argv)
    args.status = args.collect = None
    if not args.plot_only and (args.case is None or args.vary is None):
        p.error("CASE and --vary are required (unless --plot-only)")
    if args.out is None:
        if args.case is None:
            p.error("give CASE or --out")
        stem = os.path.splitext(os.path.basename(args.case))[0]
        args.out = os.path.join("out", f"sweep_{stem}")
    if args.jobs is not None and args.jobs < 1:
        p.error("--jobs must be at least 1")
    if args.cpus_per_task is not None and args.cpus_per_task < 1:
        p.error("--cpus-per-task must be at least 1")
    if args.scheduler == "slurm":
        try:
            slurm.parse_time_limit(args.time)
        except ValueError as e:
            p.error(str(e))
    return args


# ---------------------------------------------------------------------------------------------


def main(argv):
    args = parse_args(argv)
    if args.status or args.collect:
        return print_status(args.status) if args.status else collect_campaign(args.collect)
    name, values = args.vary if args.vary else campaign.values_in(args.out)
    seeds = args.seeds
    ok = True
    if not args.plot_only:
        try:
            args.coupler = runs.coupler(args.coupler)
        except SystemExit as e:
            print(e, file=sys.stderr)
            return 2
        if args.scheduler == "slurm":
            return submit_sweep(args, name, values, seeds)
        ok = run_sweep(args, name, values, seeds)
    elif seeds is None:
        seeds = campaign.seeds_in(args.out, name, values)
    return tables_and_figures(args.out, name, values, seeds, args.plot_only, ok)
