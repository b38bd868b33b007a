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
import csv
import json
import os
import signal
import subprocess
import sys
import shutil
import time

from . import runs, slurm
from .run_data import read_summary
# The figures, and the helpers the run loop shares with them.
from .sweep_figures import Sweep, as_number, draw, note, run_dir

PLAN = "sweep_plan.json"  # in the sweep folder: the runs a sweep will make

# The scene's defaults (proto/rockcut/scene.proto), used when a summary lacks
# hydrostatic_pressure_pa: p_hydro = p_atm + rho_w g water_depth_m.
P_ATM_PA = 101325.0
RHO_WATER_KG_M3 = 1025.0
GRAVITY_M_S2 = 9.81


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


def parse_seeds(text):
    """'1,2,3' -> [1, 2, 3] (distinct non-negative integers)."""
    try:
        seeds = [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected seeds like 1,2,3 , got '{text}'")
    if not seeds or len(set(seeds)) != len(seeds) or min(seeds) < 0:
        raise argparse.ArgumentTypeError(f"expected distinct seeds >= 0 like 1,2,3 , got '{text}'")
    return seeds


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


def read_plan(out):
    """The sweep's plan (sweep_plan.json: case, name, values, seeds, set), or None."""
    try:
        with open(os.path.join(out, PLAN)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def values_in(out):
    """(name, values) from the <name>=<value> folders of a sweep directory (for --plot-only)."""
    found = {}
    for d in sorted(os.listdir(out)) if os.path.isdir(out) else []:
        if "=" in d and os.path.isdir(os.path.join(out, d)):
            name, _, value = d.partition("=")
            found.setdefault(name, []).append(value)
    if len(found) != 1:
        raise SystemExit(f"sweep: cannot tell the varied parameter from {out} "
                         f"(found {sorted(found) or 'no <name>=<value> folders'}): give --vary")
    return next(iter(found.items()))


def seeds_in(out, name, values):
    """The seeds of the seed=<S> folders under the value folders (None: one run per value)."""
    seeds = set()
    for value in values:
        d = run_dir(out, name, value)
        for sub in os.listdir(d) if os.path.isdir(d) else []:
            if sub.startswith("seed=") and sub[5:].isdigit() and os.path.isdir(os.path.join(d, sub)):
                seeds.add(int(sub[5:]))
    return sorted(seeds) or None


def sorted_values(values):
    """Numeric values in increasing order; other values (e.g. model names) as given."""
    if all(as_number(v) is not None for v in values):
        return sorted(values, key=float)
    return list(values)


# ---------------------------------------------------------------------------------------------
# Running


def run_sets(args, name, value, seed):
    """The --set overrides of one run: the sweep's, the seed's, then the varied value's."""
    sets = list(args.set)
    if seed is not None:
        sets.append(f"dem.specimen.seed={seed}")
    sets.append(f"{name}={value}")  # last, so that it wins over a --set of the same field
    return sets


def earlier_run(d, cmd):
    """'done' when folder `d` holds a completed run of the command `cmd`, 'resume' when it holds
    a run of `cmd` that did not complete but left a checkpoint, else None (start afresh)."""
    try:
        with open(os.path.join(d, "sweep_run.json")) as f:
            record = json.load(f)
    except (OSError, ValueError):
        return None
    if record.get("command") != cmd:
        return None
    summary = read_summary(d) or {}
    if summary.get("status") == "completed" and record.get("exit_code") == 0:
        return "done"
    has_checkpoint = os.path.isdir(os.path.join(d, "checkpoints")) and any(
        f.endswith(".h5") for f in os.listdir(os.path.join(d, "checkpoints")))
    return "resume" if has_checkpoint else None


def clear_run(d):
    """Removes what an earlier run left in folder `d`: it must not pass for this run's results."""
    for stale in ("summary.json", "sweep_run.json", "run.h5", "run.xdmf", "log.txt",
                  slurm.EXIT_CODE_FILE):
        if os.path.exists(os.path.join(d, stale)):
            os.remove(os.path.join(d, stale))
    shutil.rmtree(os.path.join(d, "checkpoints"), ignore_errors=True)


def start_run(args, name, value, seed):
    d = run_dir(args.out, name, value, seed)
    os.makedirs(d, exist_ok=True)
    cmd = runs.command(args.case, d, run_sets(args, name, value, seed), args.coupler)
    resume = earlier_run(d, cmd) == "resume"
    if not resume:
        clear_run(d)
    log = open(os.path.join(d, "log.txt"), "a" if resume else "w")
    log.write("$ " + " ".join(cmd + (["--resume"] if resume else [])) + "\n")
    log.flush()
    proc = runs.start(cmd + (["--resume"] if resume else []), log)
    # Started, not finished: `rockcut status` tells a run still going from one whose sweep stopped.
    with open(os.path.join(d, "sweep_run.json"), "w") as f:
        json.dump({"command": cmd, "pid": proc.pid}, f, indent=1)
    return proc, log, time.monotonic(), cmd


def finish_run(args, name, value, seed, proc, log, t0, cmd):
    """Records the run's exit code beside its output (for --plot-only) and prints its line."""
    log.close()
    wall = time.monotonic() - t0
    d = run_dir(args.out, name, value, seed)
    with open(os.path.join(d, "sweep_run.json"), "w") as f:
        json.dump({"command": cmd, "exit_code": proc.returncode, "sweep_wall_s": wall}, f, indent=1)
    summary = read_summary(d)
    status = summary.get("status") if summary else "no summary.json"
    ok = proc.returncode == 0
    label = f"{name}={value}" + ("" if seed is None else f" seed={seed}")
    print(f"{label}: {'ok' if ok else 'FAILED'}, status {status}, {wall:.1f} s wall, "
          f"exit code {proc.returncode}" + ("" if ok else f"  (see {d}/log.txt)"), flush=True)
    return ok


def write_plan(args, name, values, seeds):
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, PLAN), "w") as f:  # what `rockcut status` lists as pending
        json.dump({"case": args.case, "name": name, "values": values, "seeds": seeds,
                   "set": args.set, "scheduler": args.scheduler}, f, indent=1)


def submit_sweep(args, name, values, seeds):
    """--scheduler slurm: writes the job array and submits it (or, while an earlier job of this
    sweep is queued, says so). Returns the exit status."""
    job = slurm.job_id_of(args.out)
    if job and not args.dry_run and slurm.task_states(job):
        print(f"sweep: job {job} of {args.out} is still queued or running: not submitted again")
        return collect_finished(args.out)
    if job and not args.dry_run and all(
            (read_summary(run_dir(args.out, name, v, s)) or {}).get("status") == "completed"
            for s in (seeds or [None]) for v in values):
        print(f"sweep: every run of job {job} has completed")
        return collect_finished(args.out)
    cpus = args.cpus_per_task or runs.dem_threads(args.case, args.set, args.coupler)
    scene = runs.effective_scene(args.case, args.set, args.coupler)
    coupled = "fluid" in scene_blocks(scene)
    threads = [f"dem.threads={cpus}"] + ([f"fluid.threads={cpus}"] if coupled else [])
    write_plan(args, name, values, seeds)
    tasks = []
    for value, seed in [(v, s) for s in (seeds or [None]) for v in values]:
        d = run_dir(args.out, name, value, seed)
        os.makedirs(d, exist_ok=True)
        sets = run_sets(args, name, value, seed) + threads
        argv = [a for s in sets for a in ("--set", s)]
        tasks.append((os.path.relpath(d, args.out), argv))
        cmd = runs.command(args.case, d, sets, args.coupler)
        # A folder of another command starts afresh; one of this command is resumed or, when it
        # completed, left alone by its task.
        if earlier_run(d, cmd) is None and not slurm_run_of(d, cmd):
            clear_run(d)
        with open(os.path.join(d, "sweep_run.json"), "w") as f:  # the command, no exit code yet
            json.dump({"command": cmd, "scheduler": "slurm"}, f, indent=1)
    script = slurm.write_job(args.out, args.coupler, args.case, tasks, args.time, cpus,
                             args.partition, args.account, args.sbatch_arg)
    print(f"sweep: {len(tasks)} runs of {args.case} as a Slurm job array: {script}")
    if args.dry_run:
        print(f"sweep: not submitted (--dry-run); submit with: sbatch {script}")
        return 0
    try:
        job = slurm.submit(args.out)
    except (RuntimeError, FileNotFoundError) as e:
        print(f"sweep: {e}", file=sys.stderr)
        return 1
    print(f"sweep: submitted job {job}; follow it with: scripts/rockcut status {args.out}\n"
          f"       and collect what has finished with: scripts/rockcut collect {args.out}")
    return 0


def collect_finished(out):
    """rockcut collect DIR: the CSVs and figures of what has finished, naming what is missing."""
    from . import collect as collect_verb
    code = collect_verb.main([out])
    return 0 if code in (0, 1) else code  # 1: nothing has finished yet, which is no error here


def slurm_run_of(d, cmd):
    """True when folder `d` holds a run of `cmd` that a Slurm task started (its exit code, if any,
    is in exit_code.txt rather than sweep_run.json)."""
    try:
        with open(os.path.join(d, "sweep_run.json")) as f:
            record = json.load(f)
    except (OSError, ValueError):
        return False
    return record.get("command") == cmd and record.get("scheduler") == "slurm"


def scene_blocks(scene_text):
    """The top-level blocks of a scene in text format (e.g. {'time', 'dem', 'fluid'})."""
    import re
    return set(re.findall(r"^([a-z_]+)\s*\{", scene_text, flags=re.M))


def run_sweep(args, name, values, seeds):
    """Runs every value (and seed), --jobs at a time. Returns True if all exited with 0."""
    jobs = args.jobs or runs.default_jobs(args.case, args.set, args.coupler)
    runs.side_by_side(jobs)
    # Seed by seed: the first seed's whole curve is done before the second seed starts.
    pending = [(v, s) for s in (seeds or [None]) for v in values]
    write_plan(args, name, values, seeds)
    done = [k for k in pending if earlier_run(
        run_dir(args.out, name, *k),
        runs.command(args.case, run_dir(args.out, name, *k), run_sets(args, name, *k),
                     args.coupler)) == "done"]
    if done:
        print(f"sweep: {len(done)} of {len(pending)} runs completed earlier; not run again",
              flush=True)
        pending = [k for k in pending if k not in done]
    print(f"sweep: {len(pending)} runs of {args.case} ({name} = {', '.join(values)}"
          + ("" if seeds is None else f"; seeds {', '.join(map(str, seeds))}")
          + f"), {jobs} at a time, into {args.out}", flush=True)
    running = {}  # (value, seed) -> (proc, log, t0, cmd)
    all_ok = True

    def stop(signum, frame):  # `kill` of the sweep stops its runs as Ctrl-C does
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    try:
        while pending or running:
            while pending and len(running) < jobs:
                key = pending.pop(0)
                running[key] = start_run(args, name, *key)
            time.sleep(0.2)
            for key in [k for k, r in running.items() if r[0].poll() is not None]:
                all_ok = finish_run(args, name, *key, *running.pop(key)) and all_ok
    except KeyboardInterrupt:
        # Ask the runs to stop (the coupler closes its output on SIGTERM), then insist.
        print(f"sweep: interrupted; stopping {len(running)} run(s)", file=sys.stderr)
        for proc, *_ in running.values():
            proc.send_signal(signal.SIGTERM)
        for proc, log, *_ in running.values():
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            log.close()
        raise SystemExit(130)
    return all_ok


# ---------------------------------------------------------------------------------------------
# Collecting


def collect(out, name, values, seeds=None):
    """One row (dict) per run, in the order of `values` (then `seeds`)."""
    rows = []
    for value, seed in [(v, s) for v in values for s in (seeds or [None])]:
        d = run_dir(out, name, value, seed)
        summary = read_summary(d) or {}
        row = {k: v for k, v in summary.items()
               if v is None or isinstance(v, (bool, int, float, str))}  # scalars only
        try:
            with open(os.path.join(d, "sweep_run.json")) as f:
                record = json.load(f)
            if "exit_code" in record:  # absent while the run goes (or its sweep stopped)
                row["exit_code"] = record["exit_code"]
            elif slurm.exit_code_of(d) is not None:  # a Slurm task's
                row["exit_code"] = slurm.exit_code_of(d)
        except (OSError, ValueError):
            pass  # run outside this script, or before it recorded exit codes
        if not summary:
            row["status"] = "not run" if "exit_code" not in row else "failed: no summary.json"
        # The summary's own value wins; else p_atm + rho g h for a water-depth sweep.
        depth = as_number(value) if name == "water_depth_m" else None
        if "hydrostatic_pressure_pa" not in row and depth is not None:
            row["hydrostatic_pressure_pa"] = P_ATM_PA + RHO_WATER_KG_M3 * GRAVITY_M_S2 * depth
        row[name] = value
        if seed is not None:
            row["seed"] = seed
        rows.append(row)
    return rows


def write_csv(path, name, rows):
    first = [name, "hydrostatic_pressure_pa"] + (["seed"] if any("seed" in r for r in rows) else [])
    keys = sorted(set().union(*(r.keys() for r in rows)) - set(first))
    columns = first + keys
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, restval="")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in columns})


# ---------------------------------------------------------------------------------------------


def main(argv):
    args = parse_args(argv)
    if args.status or args.collect:
        from . import collect as collect_verb, status as status_verb
        return (status_verb.main([args.status]) if args.status
                else collect_verb.main([args.collect]))
    name, values = args.vary if args.vary else values_in(args.out)
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
        seeds = seeds_in(args.out, name, values)
    rows = collect(args.out, name, sorted_values(values), seeds)
    if not any("exit_code" in r or r.get("status") not in (None, "not run") for r in rows):
        print(f"sweep: no run results in {args.out}", file=sys.stderr)
        return 1
    os.makedirs(args.out, exist_ok=True)
    failed = [f"{r[name]}" + (f" seed {r['seed']}" if "seed" in r else "")
              + f" (exit code {r['exit_code']})" for r in rows
              if r.get("exit_code") not in (0, None)]
    if args.plot_only and failed:
        note(f"runs that failed: {', '.join(failed)}")
    write_csv(os.path.join(args.out, "sweep.csv"), name, rows)
    print(f"wrote {os.path.join(args.out, 'sweep.csv')}")
    sweep = Sweep(args.out, name, rows)
    mean_csv = os.path.join(args.out, "sweep_mean.csv")
    if seeds is not None:
        write_csv(mean_csv, name, sweep.mean_rows())
        print(f"wrote {mean_csv}")
    elif os.path.exists(mean_csv):
        os.remove(mean_csv)  # from an earlier sweep with seeds in the same folder
    draw(sweep)
    if not ok:
        print("sweep: some runs failed (see above)", file=sys.stderr)
    return 0 if ok else 1

