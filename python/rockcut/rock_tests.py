"""The rock's loading tests (cases/calibration: ucs, brazilian, biaxial) for one rock file and a
set of micro-parameters on several specimen seeds, run side by side, each in a folder of its own.
A run whose folder already holds a completed summary.json of the same request is not run again, so
`rockcut calibrate --target` and `rockcut envelope` started again on their folder resume where
they stopped.

    OUT/scenes/{ucs,brazilian,biaxial}.pbtxt   the test scenes on the rock file (`base:`)
    RUN/request.json                            the scene, test and --set options of a run
    RUN/summary.json, run.h5, log.txt           the coupler's output and its log
"""
import concurrent.futures
import json
import os
import re

from . import runs
from .summary_file import read_json, read_summary

TESTS = ("ucs", "brazilian", "biaxial")
REQUEST = "request.json"


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


def run_one(run_dir, request, coupler):
    summary = finished(run_dir, request)
    if summary:
        return summary
    os.makedirs(run_dir, exist_ok=True)
    with open(os.path.join(run_dir, REQUEST), "w") as f:
        json.dump(request, f, indent=1)
    p = runs.run(request["scene"], run_dir, request["sets"], coupler,
                 log=os.path.join(run_dir, "log.txt"))
    summary = read_summary(run_dir)
    if p.returncode != 0 or not summary:
        tail = (p.stderr or p.stdout or "").strip().splitlines()[-1:] or [""]
        raise RuntimeError(f"{run_dir}: the coupler exited with {p.returncode}: {tail[0]}")
    return summary


def run_all(jobs_list, jobs, coupler=None):
    """Runs [(run_dir, scene, [--set values])] with `jobs` at a time; returns {run_dir: summary}.
    Runs already finished with the same request are reused."""
    coupler = runs.coupler(coupler)
    runs.side_by_side(jobs)
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures = {pool.submit(run_one, d, {"scene": os.path.abspath(scene), "sets": list(sets)},
                               coupler): d for d, scene, sets in jobs_list}
        for future in concurrent.futures.as_completed(futures):
            results[futures[future]] = future.result()
    return results


def micro_sets(params):
    """--set values of a parameter dict (kn, ks_ratio, tn, ts_ratio, phi_b_deg; contacts take the
    bonds' stiffnesses, as in the shipped rocks)."""
    kn, ks = params["kn"], params["kn"] * params["ks_ratio"]
    tn = params["tn"]
    return [f"dem.bonds.normal_stiffness_pa={kn:.6g}", f"dem.bonds.shear_stiffness_pa={ks:.6g}",
            f"dem.contact.normal_stiffness_pa={kn:.6g}", f"dem.contact.shear_stiffness_pa={ks:.6g}",
            f"dem.bonds.tensile_strength_n_per_m={tn:.6g}",
            f"dem.bonds.shear_strength_n_per_m={tn * params['ts_ratio']:.6g}",
            f"dem.bonds.friction_angle_deg={params['phi_b_deg']:.6g}"]
