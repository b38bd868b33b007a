"""A campaign directory: the plan of a sweep, its run folders and their states, and the tables
collected from them. Every verb that reads or writes these files does it through this module
(`rockcut sweep`, `status`, `collect`, `compare`); it starts nothing and draws nothing.

    DIR/sweep_plan.json               the plan: case, varied field, values, seeds, --set, scheduler
    DIR/<name>=<value>[/seed=<S>]/    one folder per run (run_dir): the coupler's output
                                      (summary.json, run.h5, checkpoints/), log.txt and
                                      sweep_run.json (the run's command, its pid while it goes,
                                      then its exit code; a Slurm task writes exit_code.txt)
                                      (campaign_run.py: one run's folder)
    DIR/sweep.csv, DIR/sweep_mean.csv the collected tables (collect, write_csv)
    DIR/job.sbatch, tasks.tsv, slurm_job_id, slurm_logs/   a sweep submitted to Slurm (slurm.py)
"""
import argparse
import csv
import json
import os

from . import slurm
# One run's folder in the campaign: its record, what an earlier run left, its state. Reached
# through this module by the verbs.
from .campaign_run import (LOG, RECORD, clear_run, earlier_run, read_record,  # noqa: F401
                           slurm_run_of, state, write_record)
from .summary_file import read_json, read_summary

PLAN = "sweep_plan.json"     # in the sweep folder: the runs a sweep will make
TABLE = "sweep.csv"          # one row per run
MEAN_TABLE = "sweep_mean.csv"  # with seeds: one row per value

# The fluid block's defaults (proto/rockcut/fluid_scene.proto), used when a summary lacks
# hydrostatic_pressure_pa: p_hydro = p_atm + rho_w g water_depth_m.
P_ATM_PA = 101325.0
RHO_WATER_KG_M3 = 1025.0
GRAVITY_M_S2 = 9.81


def as_number(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


# ---------------------------------------------------------------------------------------------
# The plan and the run folders


def parse_seeds(text):
    """'1,2,3' -> [1, 2, 3] (distinct non-negative integers)."""
    try:
        seeds = [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected seeds like 1,2,3 , got '{text}'")
    if not seeds or len(set(seeds)) != len(seeds) or min(seeds) < 0:
        raise argparse.ArgumentTypeError(f"expected distinct seeds >= 0 like 1,2,3 , got '{text}'")
    return seeds


def run_dir(out, name, value, seed=None):
    d = os.path.join(out, f"{name}={value}")
    return d if seed is None else os.path.join(d, f"seed={seed}")


def run_label(name, value, seed=None):
    """'water_depth_m=100 seed=2': how the verbs name a run in their lines."""
    return f"{name}={value}" + ("" if seed is None else f" seed={seed}")


def read_plan(out):
    """The sweep's plan (sweep_plan.json: case, name, values, seeds, set), or None."""
    return read_json(os.path.join(out, PLAN))


def write_plan(out, case, name, values, seeds, sets, scheduler):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, PLAN), "w") as f:  # what `rockcut status` lists as pending
        json.dump({"case": case, "name": name, "values": values, "seeds": seeds,
                   "set": sets, "scheduler": scheduler}, f, indent=1)


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


def planned_runs(out):
    """(name, values, seeds) of the sweep folder: its plan's, also of the runs that have not
    started, else those found from its folders (SystemExit when they do not tell)."""
    plan = read_plan(out)
    if plan:
        return plan["name"], plan["values"], plan.get("seeds")
    name, values = values_in(out)
    return name, values, seeds_in(out, name, values)


def run_sets(sets, name, value, seed):
    """The --set overrides of one run: the sweep's, the seed's, then the varied value's."""
    sets = list(sets)
    if seed is not None:
        sets.append(f"dem.specimen.seed={seed}")
    sets.append(f"{name}={value}")  # last, so that it wins over a --set of the same field
    return sets


def runs_of(out):
    """[(label, folder)] of every run of the sweep folder, planned or found."""
    name, values, seeds = planned_runs(out)
    return [(run_label(name, v, s), run_dir(out, name, v, s))
            for s in (seeds or [None]) for v in sorted_values(values)]


# ---------------------------------------------------------------------------------------------
# The runs' states (one run's folder: campaign_run.py)


def table(out):
    """[(label, folder, state, detail)] of the sweep folder; with the Slurm task's state in the
    detail for a sweep submitted to Slurm."""
    rows = [(label, d) + state(d) for label, d in runs_of(out)]
    job = slurm.job_id_of(out)
    if not job:
        return rows
    tasks = slurm.task_index_of_runs(out)
    queue = slurm.task_states(job)
    out_rows = []
    for label, d, st, detail in rows:
        index = tasks.get(os.path.relpath(d, out))
        where = queue.get(index) if index is not None else None
        if where is None:
            if st == "running":  # not in the queue any more and no summary: the task was lost
                st, detail = "failed", "its Slurm task ended without a summary.json"
        else:
            if where.startswith("PENDING") and st in ("pending", "running", "interrupted"):
                st = "pending" if st != "interrupted" else "interrupted"
            detail = (detail + "; " if detail else "") + f"slurm {job}_{index}: {where}"
        out_rows.append((label, d, st, detail))
    return out_rows


# ---------------------------------------------------------------------------------------------
# The collected tables


def collect(out, name, values, seeds=None):
    """One row (dict) per run, in the order of `values` (then `seeds`)."""
    rows = []
    for value, seed in [(v, s) for v in values for s in (seeds or [None])]:
        d = run_dir(out, name, value, seed)
        summary = read_summary(d) or {}
        row = {k: v for k, v in summary.items()
               if v is None or isinstance(v, (bool, int, float, str))}  # scalars only
        record = read_record(d)
        if record is not None:  # None: run outside the sweep, or before it recorded exit codes
            if "exit_code" in record:  # absent while the run goes (or its sweep stopped)
                row["exit_code"] = record["exit_code"]
            elif slurm.exit_code_of(d) is not None:  # a Slurm task's
                row["exit_code"] = slurm.exit_code_of(d)
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


def has_results(rows):
    """True when some row is of a run that ran (an exit code, or a summary)."""
    return any("exit_code" in r or r.get("status") not in (None, "not run") for r in rows)


def failed_runs(name, rows):
    """'100 seed 2 (exit code 3)' for each run that exited with an error."""
    return [f"{r[name]}" + (f" seed {r['seed']}" if "seed" in r else "")
            + f" (exit code {r['exit_code']})" for r in rows
            if r.get("exit_code") not in (0, None)]


def write_csv(path, name, rows):
    first = [name, "hydrostatic_pressure_pa"] + (["seed"] if any("seed" in r for r in rows) else [])
    keys = sorted(set().union(*(r.keys() for r in rows)) - set(first))
    columns = first + keys
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, restval="")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in columns})


def write_rows(path, rows):
    """A table of one row per run, its columns those of the first row (calibrate, study)."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
