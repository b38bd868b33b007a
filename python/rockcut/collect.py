"""rockcut collect DIR: sweep.csv, sweep_mean.csv and the figures from the runs of a sweep folder
that have finished, naming the runs that are missing (pending, running, failed, interrupted).

  rockcut collect DIR

The same as `rockcut sweep --plot-only --out DIR` (the varied field and the seeds are found from
DIR's folders), for a sweep that is still going or was stopped: the figures draw what has finished.
Exit status: 0 once drawn, 1 if DIR holds no finished run, 2 when DIR is not a sweep folder.
"""
import argparse
import os
import sys

from . import status, sweep



def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut collect", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", metavar="DIR", help="a sweep folder")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.out):
        print(f"rockcut collect: {a.out}: no such folder", file=sys.stderr)
        return 2
    try:
        rows = status.table(a.out)
    except SystemExit as e:
        print(e, file=sys.stderr)
        return 2
    missing = [(label, st, detail) for label, _, st, detail in rows if st != "done"]
    for label, st, detail in missing:
        print(f"missing: {label} ({st}{': ' + detail if detail else ''})", file=sys.stderr)
    if len(missing) == len(rows):
        print(f"rockcut collect: no finished run in {a.out}", file=sys.stderr)
        return 1
    argv = ["--plot-only", "--out", a.out]
    plan = sweep.read_plan(a.out)
    if plan:  # the planned values and seeds, also those that have not run yet
        argv += ["--vary", f"{plan['name']}=" + ",".join(plan["values"])]
        if plan.get("seeds"):
            argv += ["--seeds", ",".join(map(str, plan["seeds"]))]
    code = sweep.main(argv)
    print(f"collected {len(rows) - len(missing)} of {len(rows)} runs"
          + (f"; missing {len(missing)} (listed above)" if missing else ""))
    return code
