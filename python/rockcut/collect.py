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

from . import campaign
from .sweep_figures import draw
from .sweep_table import Sweep, note


def tables_and_figures(out, name, values, seeds, plot_only=False, ok=True):
    """Collects DIR/sweep.csv (and with seeds DIR/sweep_mean.csv) from the runs of the sweep
    folder `out` and draws its figures; `ok`: whether the runs just made all succeeded. Returns
    the exit status of rockcut sweep (1: no run results, or a run failed)."""
    rows = campaign.collect(out, name, campaign.sorted_values(values), seeds)
    if not campaign.has_results(rows):
        print(f"sweep: no run results in {out}", file=sys.stderr)
        return 1
    os.makedirs(out, exist_ok=True)
    failed = campaign.failed_runs(name, rows)
    if plot_only and failed:
        note(f"runs that failed: {', '.join(failed)}")
    campaign.write_csv(os.path.join(out, campaign.TABLE), name, rows)
    print(f"wrote {os.path.join(out, campaign.TABLE)}")
    sweep = Sweep(out, name, rows)
    mean_csv = os.path.join(out, campaign.MEAN_TABLE)
    if seeds is not None:
        campaign.write_csv(mean_csv, name, sweep.mean_rows())
        print(f"wrote {mean_csv}")
    elif os.path.exists(mean_csv):
        os.remove(mean_csv)  # from an earlier sweep with seeds in the same folder
    draw(sweep)
    if not ok:
        print("sweep: some runs failed (see above)", file=sys.stderr)
    return 0 if ok else 1


def collect_campaign(out):
    """The verb: the tables and figures of what has finished in the sweep folder `out`, naming what
    is missing. Returns the exit status."""
    if not os.path.isdir(out):
        print(f"rockcut collect: {out}: no such folder", file=sys.stderr)
        return 2
    try:
        rows = campaign.table(out)
    except SystemExit as e:
        print(e, file=sys.stderr)
        return 2
    missing = [(label, st, detail) for label, _, st, detail in rows if st != "done"]
    for label, st, detail in missing:
        print(f"missing: {label} ({st}{': ' + detail if detail else ''})", file=sys.stderr)
    if len(missing) == len(rows):
        print(f"rockcut collect: no finished run in {out}", file=sys.stderr)
        return 1
    plan = campaign.read_plan(out)
    if plan:  # the planned values and seeds, also those that have not run yet
        name, values, seeds = plan["name"], plan["values"], plan.get("seeds") or None
    else:
        (name, values), seeds = campaign.values_in(out), None
    if seeds is None:
        seeds = campaign.seeds_in(out, name, values)
    code = tables_and_figures(out, name, values, seeds, plot_only=True)
    print(f"collected {len(rows) - len(missing)} of {len(rows)} runs"
          + (f"; missing {len(missing)} (listed above)" if missing else ""))
    return code


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut collect", description=__doc__.split("\n")[0],
                                 epilog="\n".join(__doc__.split("\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", metavar="DIR", help="a sweep folder")
    a = ap.parse_args(argv)
    return collect_campaign(a.out)
