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
import os
import sys

from . import campaign


def print_status(out):
    """The verb: one line per run of the sweep folder `out` and a count of each state. Returns
    the exit status."""
    if not os.path.isdir(out):
        print(f"rockcut status: {out}: no such folder", file=sys.stderr)
        return 2
    try:
        rows = campaign.table(out)
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


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut status", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", metavar="DIR", help="a sweep folder")
    a = ap.parse_args(argv)
    return print_status(a.out)
