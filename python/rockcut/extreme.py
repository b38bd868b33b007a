"""Stiff and extreme scenes (cases/extreme/*.pbtxt): run each, and say whether it ran stably, was
refused at start-up, or was stopped by a runtime guard.

  rockcut extreme [--jobs N] [--out DIR] [--only NAME,NAME] [--no-halve] [--coupler PATH]

Each scene runs as given and, unless --no-halve, again with the DEM step halved
(--set time.dt_safety=0.1, the default being 0.2), so that the table shows whether the results
converge when the step halves. Writes DIR/extreme.md (a markdown table, what docs/record/accuracy.md
quotes) and DIR/extreme.csv, one row per run, and prints the table.

Outcome of a run:
  stable    exit 0, and the energy imbalance below 2 % (the bound of the cutting tests)
  refused   exit 2 at start-up: the message names the limit, the factor and what to change
  guard     exit 4: a runtime guard stopped it (the reason is in the table)
  failed    anything else
Exit status: 0 when every scene is stable or refused, 1 otherwise.
"""
import argparse
import concurrent.futures
import csv
import glob
import os
import re
import sys

from . import runs
from .run_data import read_summary

IMBALANCE_BOUND = 0.02


def run_case(coupler, scene, out, extra):
    os.makedirs(out, exist_ok=True)
    p = runs.run(scene, out, extra, coupler, log=os.path.join(out, "log.txt"))
    row = {"scene": os.path.splitext(os.path.basename(scene))[0],
           "dt_safety": "0.1" if extra else "0.2", "exit": p.returncode}
    summary = read_summary(out) or {}
    m = re.search(r"chosen coupling interval N = (\d+).*?\(([^)]*)\)", p.stderr)
    row["N"] = m.group(1) if m else ""
    row["N_binding"] = m.group(2).replace("binding: ", "") if m else ""
    m = re.search(r"chosen dt = (\S+) s", p.stderr)
    row["dt_s"] = m.group(1) if m else ""
    for key in ("force_horizontal_mean_n_per_m", "force_vertical_mean_n_per_m", "breaks_tensile",
                "breaks_shear", "energy_imbalance_rel", "wall_time_s", "peclet_number",
                "failure_guard", "failure_time_s"):
        value = summary.get(key)  # null: a run stopped before its steady part has no mean
        row[key] = "" if value is None else value
    imbalance = summary.get("energy_imbalance_rel")
    if p.returncode == 0:
        ok = imbalance is None or imbalance < IMBALANCE_BOUND
        row["outcome"] = "stable" if ok else "energy imbalance %.3g" % imbalance
    elif p.returncode == 2:
        row["outcome"] = "refused"
    elif p.returncode == 4:
        row["outcome"] = "guard " + str(summary.get("failure_guard", "?"))
    else:
        row["outcome"] = "failed (exit %d)" % p.returncode
    refusal = [l for l in p.stderr.splitlines() if "refused" in l]
    row["message"] = refusal[0].split("refused", 1)[1].lstrip(": ") if refusal else summary.get("error", "")
    return row


def fmt(v, spec):
    return (spec % v) if isinstance(v, (int, float)) and v != "" else str(v)


def table(rows):
    lines = ["| scene | dt_safety | outcome | N (binding) | Fh [kN/m] | breaks t/s | energy imbalance | wall [s] | note |",
             "|---|---:|---|---|---:|---:|---:|---:|---|"]
    for r in rows:
        fh = r["force_horizontal_mean_n_per_m"]
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["scene"], r["dt_safety"], r["outcome"],
            ("%s (%s)" % (r["N"], r["N_binding"])) if r["N"] else "",
            fmt(fh / 1e3 if fh != "" else "", "%.0f"),
            "%s/%s" % (r["breaks_tensile"], r["breaks_shear"]) if r["breaks_tensile"] != "" else "",
            fmt(r["energy_imbalance_rel"], "%.2g"), fmt(r["wall_time_s"], "%.0f"),
            r["message"][:160].replace("|", "/")))
    return "\n".join(lines) + "\n"


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut extreme", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=runs.default_out("extreme"))
    ap.add_argument("--only", default="")
    ap.add_argument("--no-halve", action="store_true")
    ap.add_argument("--coupler", help="the coupler to run (default build/bin/coupler)")
    a = ap.parse_args(argv)
    a.coupler = runs.coupler(a.coupler)
    scenes = sorted(glob.glob(runs.case("extreme", "*.pbtxt")))
    if a.only:
        wanted = set(a.only.split(","))
        scenes = [s for s in scenes if os.path.splitext(os.path.basename(s))[0] in wanted]
        if not scenes:
            sys.exit("rockcut extreme: no scene in cases/extreme matches --only " + a.only)
    jobs = []
    for s in scenes:
        name = os.path.splitext(os.path.basename(s))[0]
        jobs.append((s, os.path.join(a.out, name), []))
        if not a.no_halve:
            jobs.append((s, os.path.join(a.out, name + "_dt_half"), ["time.dt_safety=0.1"]))
    rows = []
    runs.side_by_side(a.jobs)
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        futures = [pool.submit(run_case, a.coupler, *j) for j in jobs]
        for f in concurrent.futures.as_completed(futures):
            r = f.result()
            print("%-30s dt_safety %s: %s" % (r["scene"], r["dt_safety"], r["outcome"]), flush=True)
            rows.append(r)
    rows.sort(key=lambda r: (r["scene"], r["dt_safety"] != "0.2"))
    text = table(rows)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "extreme.md"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "extreme.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(text)
    bad = [r for r in rows if r["outcome"] not in ("stable", "refused")]
    return 1 if bad else 0

