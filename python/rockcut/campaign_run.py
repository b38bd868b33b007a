"""One run's folder in a campaign directory (campaign.py): the record the sweep keeps beside the
coupler's output (sweep_run.json: the run's command, its pid while it goes, then its exit code),
what an earlier run left there, and the run's state as `rockcut status` reports it.
"""
import json
import os
import re
import shutil

from . import slurm
from .summary_file import read_json, read_summary

RECORD = "sweep_run.json"    # in a run's folder: the command that made it and how it ended
LOG = "log.txt"              # in a run's folder: the command line and the coupler's output


def read_record(d):
    """sweep_run.json of the run folder `d` as a dict, or None."""
    return read_json(os.path.join(d, RECORD))


def write_record(d, record):
    with open(os.path.join(d, RECORD), "w") as f:
        json.dump(record, f, indent=1)


def earlier_run(d, cmd):
    """'done' when folder `d` holds a completed run of the command `cmd`, 'resume' when it holds
    a run of `cmd` that did not complete but left a checkpoint, else None (start afresh)."""
    record = read_record(d)
    if record is None or record.get("command") != cmd:
        return None
    summary = read_summary(d) or {}
    if summary.get("status") == "completed" and record.get("exit_code") == 0:
        return "done"
    has_checkpoint = os.path.isdir(os.path.join(d, "checkpoints")) and any(
        f.endswith(".h5") for f in os.listdir(os.path.join(d, "checkpoints")))
    return "resume" if has_checkpoint else None


def slurm_run_of(d, cmd):
    """True when folder `d` holds a run of `cmd` that a Slurm task started (its exit code, if any,
    is in exit_code.txt rather than sweep_run.json)."""
    record = read_record(d)
    return record is not None and record.get("command") == cmd and record.get("scheduler") == "slurm"


def clear_run(d):
    """Removes what an earlier run left in folder `d`: it must not pass for this run's results."""
    for stale in ("summary.json", RECORD, "run.h5", "run.xdmf", LOG, slurm.EXIT_CODE_FILE):
        if os.path.exists(os.path.join(d, stale)):
            os.remove(os.path.join(d, stale))
    shutil.rmtree(os.path.join(d, "checkpoints"), ignore_errors=True)


# ---------------------------------------------------------------------------------------------
# The state of a run (rockcut status)


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
        with open(os.path.join(d, LOG), errors="replace") as f:
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
    """(state, detail) of the run in folder `d`: pending, running, done, failed or interrupted
    (status.py's doc says what each means)."""
    summary = read_summary(d)
    log = read_log(d)
    record = read_record(d) or {}
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


