"""The rock's loading tests (cases/calibration: ucs, brazilian, biaxial, fracture) for one rock file and a
set of micro-parameters on several specimen seeds, each in a folder of its own: side by side on
this machine (--jobs), or as Slurm job arrays (slurm.py, the script `rockcut sweep --scheduler
slurm` submits), one array per test scene. A run whose folder already holds a completed
summary.json of the same request is not run again, so `rockcut calibrate --target` and
`rockcut envelope` started again on their folder resume where they stopped.

    OUT/scenes/{ucs,brazilian,biaxial,fracture}.pbtxt   the test scenes on the rock file (`base:`)
    .../<test>/seed=<S>/                        one run: request.json (its scene and --set
                                                options), the coupler's output, log.txt
    .../<test>/job.sbatch, tasks.tsv, ...       with Slurm: that test's job array
"""
import concurrent.futures
import json
import os
import re
import shutil
import time

from . import campaign, runs, slurm
from .summary_file import read_json, read_summary

TESTS = ("ucs", "brazilian", "biaxial", "fracture")
REQUEST = "request.json"
# With Slurm: how often the folders are looked at, and how long nothing may change (no run's log
# grows, no run ends) before the wait gives up and names the runs still missing.
POLL_S = 2.0
STALL_S = 1800.0


def write_scenes(out, rock):
    """The three test scenes in OUT/scenes/, their rock the file `rock` (absolute path in `base:`)
    instead of the default rock; returns {test: path}. The scenes are the shipped ones, so their
    loading and output settings stay in one place."""
    folder = os.path.join(out, "scenes")
    os.makedirs(folder, exist_ok=True)
    rock = os.path.abspath(rock)
    paths = {}
    for test in TESTS:
        with open(runs.case("calibration", f"{test}.pbtxt")) as f:
            text = f.read()
        if test != "biaxial":  # biaxial's base is ucs.pbtxt, which sits beside it here too
            text, n = re.subn(r'^base: ".*"', f'base: "{rock}"', text, count=1, flags=re.M)
            if n != 1:
                raise SystemExit(f"rockcut: cases/calibration/{test}.pbtxt has no base line")
        paths[test] = os.path.join(folder, f"{test}.pbtxt")
        with open(paths[test], "w") as f:
            f.write(text)
    return paths


def finished(run_dir, request):
    """The summary of an earlier run of the same request that completed, or None."""
    if read_json(os.path.join(run_dir, REQUEST)) != request:
        return None
    summary = read_summary(run_dir)
    return summary if summary and summary.get("status") == "completed" else None


def prepare(run_dir, request):
    """The run's folder, its request written first: emptied when it holds another request's run,
    kept (checkpoints, for --resume on Slurm) when it holds an unfinished run of this one."""
    if read_json(os.path.join(run_dir, REQUEST)) != request:
        shutil.rmtree(run_dir, ignore_errors=True)
    os.makedirs(run_dir, exist_ok=True)
    for name in ("summary.json", slurm.EXIT_CODE_FILE):
        try:
            os.remove(os.path.join(run_dir, name))
        except FileNotFoundError:
            pass
    with open(os.path.join(run_dir, REQUEST), "w") as f:
        json.dump(request, f, indent=1)


def failure(run_dir, code):
    log = os.path.join(run_dir, "log.txt")
    try:
        with open(log, errors="replace") as f:
            tail = [line for line in f.read().strip().splitlines() if line.strip()][-1:]
    except OSError:
        tail = []
    return RuntimeError(f"{run_dir}: the coupler exited with {code}: {tail[0] if tail else ''}")


def run_one(run_dir, request, coupler):
    prepare(run_dir, request)
    p = runs.run(request["scene"], run_dir, request["sets"], coupler,
                 log=os.path.join(run_dir, "log.txt"))
    summary = read_summary(run_dir)
    if p.returncode != 0 or not summary:
        raise failure(run_dir, p.returncode)
    return summary


def run_local(pending, jobs, coupler):
    runs.side_by_side(jobs)
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = {pool.submit(run_one, d, request, coupler): d for d, request in pending}
        for future in concurrent.futures.as_completed(futures):
            results[futures[future]] = future.result()
    return results


def run_slurm(pending, coupler, options):
    """One job array per folder of runs (each holds one test's seeds, one scene), submitted with
    `options` (time, partition, account, sbatch_args); waits until every run has its exit code."""
    arrays = {}
    for d, request in pending:
        arrays.setdefault(os.path.dirname(d), []).append((d, request))
    for folder, group in arrays.items():
        scenes = {request["scene"] for _, request in group}
        if len(scenes) != 1:
            raise AssertionError(f"{folder}: runs of several scenes in one job array")
        tasks = []
        for d, request in group:
            prepare(d, request)
            tasks.append((os.path.basename(d),
                          [a for s in request["sets"] + ["dem.threads=1"] for a in ("--set", s)]))
        slurm.write_job(folder, coupler, scenes.pop(), tasks, options["time"], 1,
                        options.get("partition"), options.get("account"),
                        options.get("sbatch_args", ()))
        job = slurm.submit(folder)
        print(f"  {len(tasks)} runs of {os.path.basename(folder)} as Slurm job {job}", flush=True)
    results, last, last_change = {}, None, time.monotonic()
    while len(results) < len(pending):
        seen = []
        for d, _ in pending:
            if d in results:
                continue
            code = slurm.exit_code_of(d)
            if code is None:
                log = os.path.join(d, "log.txt")
                seen.append((d, os.path.getsize(log) if os.path.exists(log) else -1))
                continue
            summary = read_summary(d)
            if code != 0 or not summary:
                raise failure(d, code)
            results[d] = summary
        if seen != last:
            last, last_change = seen, time.monotonic()
        elif time.monotonic() - last_change > STALL_S:
            raise RuntimeError(f"no Slurm task of {len(seen)} runs has moved for {STALL_S:.0f} s "
                               f"(squeue; their logs in .../slurm_logs): {seen[0][0]} ...")
        if len(results) < len(pending):
            time.sleep(POLL_S)
    return results


def run_all(jobs_list, jobs, coupler=None, slurm_options=None):
    """Runs [(run_dir, scene, [--set values])]: `jobs` at a time here, or as Slurm job arrays
    with `slurm_options` (time, partition, account, sbatch_args); returns {run_dir: summary}.
    Runs already finished with the same request are read back."""
    coupler = runs.coupler(coupler)
    results, pending = {}, []
    for d, scene, sets in jobs_list:
        request = {"scene": os.path.abspath(scene), "sets": list(sets)}
        summary = finished(d, request)
        if summary:
            results[d] = summary
        else:
            pending.append((d, request))
    if pending:
        results.update(run_slurm(pending, coupler, slurm_options) if slurm_options
                       else run_local(pending, jobs, coupler))
    return results


def add_run_options(parser, set_help):
    """The options `rockcut calibrate --target` and `rockcut envelope` share: seeds, --set, --jobs,
    --scheduler local|slurm with the Slurm job's options (as `rockcut sweep` has them), --coupler."""
    parser.add_argument("--seeds", type=campaign.parse_seeds, default=[1, 2, 3, 4],
                        help="specimen seeds (default 1,2,3,4)")
    parser.add_argument("--set", action="append", default=[], metavar="PATH=VALUE", help=set_help)
    parser.add_argument("--jobs", type=int, default=runs.cpu_count(), help="runs at once")
    parser.add_argument("--coupler", default=None, help="the coupler (default: as runs.py finds it)")
    parser.add_argument("--scheduler", choices=("local", "slurm"), default="local",
                        help="run here (--jobs at a time) or as Slurm job arrays (default local)")
    parser.add_argument("--time", default="01:00:00",
                        help="Slurm: each task's time limit (default 01:00:00)")
    parser.add_argument("--partition", default=None, help="Slurm: the partition")
    parser.add_argument("--account", default=None, help="Slurm: the account")
    parser.add_argument("--sbatch-arg", action="append", default=[], metavar="ARG",
                        help="Slurm: one more #SBATCH line, e.g. --sbatch-arg=--qos=short")


def slurm_options(args):
    """The options run_all takes from add_run_options' arguments (None: run here)."""
    if args.scheduler != "slurm":
        return None
    try:
        slurm.parse_time_limit(args.time)  # a bad limit is said now, not by sbatch later
    except ValueError as e:
        raise SystemExit(f"rockcut: --time: {e}")
    return {"time": args.time, "partition": args.partition, "account": args.account,
            "sbatch_args": args.sbatch_arg}


def micro_sets(params):
    """--set values of a parameter dict (kn, ks_ratio, tn, ts_ratio, phi_b_deg and softening;
    contacts take the bonds' stiffnesses, as in the shipped rocks)."""
    kn, ks = params["kn"], params["kn"] * params["ks_ratio"]
    tn = params["tn"]
    return [f"dem.bonds.normal_stiffness_pa={kn:.6g}", f"dem.bonds.shear_stiffness_pa={ks:.6g}",
            f"dem.contact.normal_stiffness_pa={kn:.6g}", f"dem.contact.shear_stiffness_pa={ks:.6g}",
            f"dem.bonds.tensile_strength_n_per_m={tn:.6g}",
            f"dem.bonds.shear_strength_n_per_m={tn * params['ts_ratio']:.6g}",
            f"dem.bonds.friction_angle_deg={params['phi_b_deg']:.6g}"] + (
        [f"dem.bonds.softening_ratio={params['softening']:.6g}"] if "softening" in params else [])
