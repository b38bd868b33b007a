"""rockcut status DIR: the state of each run of a sweep folder.

  rockcut status DIR

DIR is a folder of `rockcut sweep` (DIR/<name>=<value>[/seed=<S>]/). One line per run:
  pending      not started yet (listed from DIR/sweep_plan.json, which the sweep writes first)
  running      its coupler is alive: simulated time, share of the steps and the ETA from its
               progress line (log.txt)
  done         exited with 0: its wall time
  failed       its exit code and the error line (summary.json's error, else the log's last line
               that says error or refused)
  interrupted  its sweep was stopped (Ctrl-C, kill) before it ended, or the run was stopped by a
               signal: it holds what it wrote so far (rockcut plot, rockcut windows read it);
               re-running the sweep continues it from its last checkpoint
For a sweep submitted to Slurm (rockcut sweep --scheduler slurm) each line also gives the task's
Slurm state while the job array is queued or running (e.g. "slurm: PENDING (BeginTime)" for a task
requeued at its time limit).
Exit status: 0 once listed, 2 when DIR is not a sweep folder.
"""
import argparse
import json
import os
import re
import sys

from . import slurm
from .run_data import read_summary
from .sweep import read_plan, seeds_in, sorted_values, values_in
from .sweep_figures import run_dir


PROGRESS = re.compile(r"t = (\S+) / (\S+) s\s+step (\d+) / (\d+)\s+wall (\S+) s\s+ETA (\S+) s")


def alive(pid):
    """True when process `pid` exists and is a coupler (not a recycled pid)."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            return b"coupler" in f.read()
    except (OSError, TypeError):
        return False


def read_log(d):
    try:
        with open(os.path.join(d, "log.txt"), errors="replace") as f:
            return f.read()
    except OSError:
        return None


def error_line(summary, log):
    if summary and summary.get("error"):
        return str(summary["error"])
    lines = [l.strip() for l in re.split(r"[\r\n]", log or "") if l.strip()]
    said = [l for l in lines if re.search(r"error|refused", l, re.I)]
    return (said or lines or ["no output"])[-1]


def progress(log):
    """'t = 0.012 / 0.07 s, 17 % of the steps, ETA 41 s' from the newest progress line, or ''."""
    found = PROGRESS.findall(log or "")
    if not found:
        return "started, no progress line yet"
    t, end, step, steps, _, eta = found[-1]
    share = 100.0 * int(step) / int(steps) if int(steps) else 0.0
    return f"t = {t} / {end} s, {share:.0f} % of the steps, ETA {float(eta):.0f} s"


def state(d):
    """(state, detail) of the run in folder `d` (see the module's doc)."""
    summary = read_summary(d)
    log = read_log(d)
    try:
        with open(os.path.join(d, "sweep_run.json")) as f:
            record = json.load(f)
    except (OSError, ValueError):
        record = {}
    if log is None and summary is None:
        return "pending", ""
    status = (summary or {}).get("status")
    code = record.get("exit_code")
    if code is None:
        code = slurm.exit_code_of(d)
    if status == "completed" and code in (0, None):
        return "done", f"{summary.get('wall_time_s', float('nan')):.1f} s wall"
    if status == "interrupted" or (code is not None and code >= 128):
        return "interrupted", (summary or {}).get("error", f"exit code {code}")
    if code is not None or status == "failed":
        return "failed", f"exit code {code}: {error_line(summary, log)}"
    if "pid" in record and alive(record["pid"]):
        return "running", progress(log)
    if record.get("scheduler") == "slurm" and status is None:
        return "running", progress(log)
    return "interrupted", "stopped before it ended (no exit code recorded): " + progress(log)


def runs_of(out):
    """[(label, folder)] of every run of the sweep folder, planned or found."""
    plan = read_plan(out)
    if plan:
        name, values, seeds = plan["name"], plan["values"], plan.get("seeds")
    else:
        name, values = values_in(out)
        seeds = seeds_in(out, name, values)
    return [(f"{name}={v}" + ("" if s is None else f" seed={s}"), run_dir(out, name, v, s))
            for s in (seeds or [None]) for v in sorted_values(values)]


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


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut status", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", metavar="DIR", help="a sweep folder")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.out):
        print(f"rockcut status: {a.out}: no such folder", file=sys.stderr)
        return 2
    try:
        rows = table(a.out)
    except SystemExit as e:
        print(e, file=sys.stderr)
        return 2
    width = max(len(label) for label, *_ in rows)
    counts = {}
    for label, _, st, detail in rows:
        counts[st] = counts.get(st, 0) + 1
        print(f"{label:<{width}}  {st:<11}  {detail}".rstrip())
    print(", ".join(f"{n} {s}" for s, n in counts.items()))
    return 0
