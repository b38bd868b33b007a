"""Work-precision study of coupled cutting (docs/record/accuracy.md): error against wall time.

  rockcut accuracy [--jobs N] [--out DIR] [--seeds 1,2,3,4] [--plot-only] [--coupler PATH]

On cases/cutting/saturated_reduced.pbtxt, cut short to 24 mm (steady from 10 mm), four ladders
vary one setting each from the defaults:
  dt_safety   time.dt_safety        0.4, 0.2 (default), 0.1, 0.05, 0.025
  N           coupling.interval     14 (the largest the limits allow), 7, 3 (the coupler's choice,
                                    coupling.interval_fraction 0.25 of the largest), 1 (no lag)
  h           fluid.smoothing_length_m / mean diameter   1.67, 2.5 (default), 3.33
  size        disc radii x 1.5, 1 (default), 0.75, 0.5, with the bond strengths and h scaled alike
              (a 2D bond's strength acts over about one diameter: see the scene's header)
Every setting runs once per seed (specimens differ, the physics does not). The error of a setting
is |mean over seeds - mean over seeds of the ladder's finest setting| / |finest|, for the mean
horizontal and vertical force, the total bond breaks and the node pressures P1-P3. The seed
scatter (standard error of the mean over seeds) is reported beside it: an error below the scatter
is not resolved by the study.

Writes DIR/accuracy.csv (one row per run), DIR/accuracy.md (the table), DIR/work_precision.png
(error of the mean horizontal force against wall time, log-log, one line per ladder) and
DIR/expected_error.csv, the error of the mean horizontal force per ladder setting in the variables
of the coupler's start-up estimate (coupler/data/expected_error.csv has this form): dt_safety,
fluid_step_ratio (N dt / the pore_fluid_stiffness limit, from the runs' start-up reports),
h_per_diameter and size_scale.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import sys

from . import runs
from .run_data import read_summary, scalar_fields
from .stats import mean, sem



def scene():
    """The study's scene, the default saturated reduced cut."""
    return runs.case("cutting", "saturated_reduced.pbtxt")
BASE = ["time.end_time_s=0.025", "dem.tool.steady_after_m=0.01", "output.frame_interval_s=0"]
KEYS = ["force_horizontal_mean_n_per_m", "force_vertical_mean_n_per_m", "breaks",
        "pressure_p1_mean_pa", "pressure_p2_mean_pa", "pressure_p3_mean_pa"]


def scene_sizes(scene_text):
    """The scene's own radii, bond strengths and smoothing length, which the size ladder scales:
    {set path: value} from its effective text (runs.effective_scene: the rock lives in a base)."""
    specimen, bonds = scalar_fields(scene_text, "specimen"), scalar_fields(scene_text, "bonds")
    return {"dem.specimen.radius_min_m": specimen["radius_min_m"],
            "dem.specimen.radius_max_m": specimen["radius_max_m"],
            "dem.bonds.tensile_strength_n_per_m": bonds["tensile_strength_n_per_m"],
            "dem.bonds.shear_strength_n_per_m": bonds["shear_strength_n_per_m"],
            "fluid.smoothing_length_m": scalar_fields(scene_text, "fluid")["smoothing_length_m"]}


def size_sets(scale, sizes):
    """--set overrides that scale the disc size by `scale`, with the bond strengths and h alike
    (none without `sizes`: the labels only, for reading a study)."""
    if sizes is None:
        return []
    return ["%s=%g" % (k, v * scale) for k, v in sizes.items()]


def ladders(sizes):
    """ladder -> [(label, value, --set list)], coarsest first, finest last."""
    return {
    "dt_safety": [("0.4", 0.4, ["time.dt_safety=0.4"]), ("0.2", 0.2, []),
                  ("0.1", 0.1, ["time.dt_safety=0.1"]), ("0.05", 0.05, ["time.dt_safety=0.05"]),
                  ("0.025", 0.025, ["time.dt_safety=0.025"])],
    "N": [("14", 14, ["coupling.interval=14"]), ("7", 7, ["coupling.interval=7"]),
          ("3", 3, []), ("1", 1, ["coupling.interval=1"])],
    "h": [("3.33", 3.33, ["fluid.smoothing_length_m=0.008"]), ("2.5", 2.5, []),
          ("1.67", 1.67, ["fluid.smoothing_length_m=0.004"])],
    "size": [("1.5", 1.5, size_sets(1.5, sizes)), ("1", 1.0, []),
             ("0.75", 0.75, size_sets(0.75, sizes)), ("0.5", 0.5, size_sets(0.5, sizes))],
    }


LADDER_NAMES = ("dt_safety", "N", "h", "size")
DEFAULT = {"dt_safety": "0.2", "N": "3", "h": "2.5", "size": "1"}


def run_dir(out, ladder, label, seed):
    # The default setting is shared by all ladders: run once.
    if DEFAULT[ladder] == label:
        return os.path.join(out, "default_seed%d" % seed)
    return os.path.join(out, "%s=%s_seed%d" % (ladder, label, seed))


def run(coupler, out_dir, sets, seed):
    if os.path.exists(os.path.join(out_dir, "summary.json")):
        return out_dir
    os.makedirs(out_dir, exist_ok=True)
    runs.run(scene(), out_dir, BASE + sets + ["dem.specimen.seed=%d" % seed], coupler,
             log=os.path.join(out_dir, "log.txt"))
    return out_dir


def read(out_dir):
    s = read_summary(out_dir)
    if s is None or s.get("status") != "completed":
        return None
    s["breaks"] = s.get("breaks_tensile", 0) + s.get("breaks_shear", 0)
    return s


# A ladder of the study -> the coupler's name of its variable (coupler/observers/expected_error.hpp).
MODEL_LADDERS = {"dt_safety": "dt_safety", "N": "fluid_step_ratio", "h": "h_per_diameter",
                 "size": "size_scale"}


def fluid_step_per_interval(log):
    """dt / the pore_fluid_stiffness limit from a run's start-up report (log.txt), or None: the
    fluid step ratio of a coupling interval N is N times it."""
    try:
        with open(log) as f:
            text = f.read()
    except OSError:
        return None
    limit = re.search(r"pore_fluid_stiffness: dt <= (\S+) s", text)
    dt = re.search(r"chosen dt = (\S+) s", text)
    return float(dt.group(1)) / float(limit.group(1)) if limit and dt else None


def model_rows(out, table, seeds):
    """The rows of expected_error.csv: ladder (the model's variable), value, force_error, seeds."""
    rows = []
    per_n = fluid_step_per_interval(os.path.join(run_dir(out, "N", "1", seeds[0]), "log.txt"))
    for e in table:
        if e.get("missing"):
            continue
        value = e["value"]
        if e["ladder"] == "N":
            if per_n is None:
                continue  # no start-up report to place N against the limit
            value *= per_n
        rows.append({"ladder": MODEL_LADDERS[e["ladder"]], "value": "%.4g" % value,
                     "force_error": "%.4f" % e["error_force_horizontal_mean_n_per_m"],
                     "seeds": e["runs"]})
    return rows


def analyse(out, seeds, ladders_=None):
    rows, table = [], []
    for ladder, settings in (ladders_ or ladders(None)).items():
        done = {}
        for label, value, _ in settings:
            ss = [read(run_dir(out, ladder, label, seed)) for seed in seeds]
            done[label] = [s for s in ss if s]
            for seed, s in zip(seeds, ss):
                if s:
                    rows.append(dict({"ladder": ladder, "setting": label, "seed": seed,
                                      "wall_time_s": s["wall_time_s"]}, **{k: s.get(k) for k in KEYS}))
        finest = settings[-1][0]
        if not done[finest]:
            continue
        ref = {k: mean([s[k] for s in done[finest]]) for k in KEYS}
        for label, value, _ in settings:
            rs = done[label]
            if not rs:
                table.append({"ladder": ladder, "setting": label, "missing": True})
                continue
            entry = {"ladder": ladder, "setting": label, "value": value, "runs": len(rs),
                     "wall_time_s": mean([s["wall_time_s"] for s in rs]),
                     "coupling_interval": rs[0].get("coupling_interval"),
                     "particles": rs[0].get("particles")}
            for k in KEYS:
                m = mean([s[k] for s in rs])
                entry["error_" + k] = abs(m - ref[k]) / abs(ref[k]) if ref[k] else float("nan")
                entry["scatter_" + k] = sem([s[k] for s in rs]) / abs(ref[k]) if ref[k] else float("nan")
            table.append(entry)
    return rows, table


SHORT = {"force_horizontal_mean_n_per_m": "Fh", "force_vertical_mean_n_per_m": "Fv",
         "breaks": "breaks", "pressure_p1_mean_pa": "P1", "pressure_p2_mean_pa": "P2",
         "pressure_p3_mean_pa": "P3"}


def markdown(table, seeds):
    head = "| ladder | setting | N | particles | wall [s] | " + " | ".join(
        "%s err (scatter)" % SHORT[k] for k in KEYS) + " |"
    lines = [head, "|" + "---|" * (5 + len(KEYS))]
    for e in table:
        if e.get("missing"):
            lines.append("| %s | %s | | | | %s |" % (e["ladder"], e["setting"], " | ".join("-" for _ in KEYS)))
            continue
        cells = ["%.0f %% (%.0f %%)" % (100 * e["error_" + k], 100 * e["scatter_" + k]) for k in KEYS]
        lines.append("| %s | %s | %s | %s | %.1f | %s |" % (
            e["ladder"], e["setting"], e["coupling_interval"], e["particles"], e["wall_time_s"],
            " | ".join(cells)))
    return ("Errors against the finest setting of each ladder (mean over seeds %s); in brackets the\n"
            "standard error of the mean over the seeds, relative to the finest value.\n\n"
            % ",".join(map(str, seeds))) + "\n".join(lines) + "\n"


def plot(table, path):
    from .figures import plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for ladder in LADDER_NAMES:
        es = [e for e in table if e["ladder"] == ladder and not e.get("missing")][:-1]  # not the reference
        if not es:
            continue
        x = [e["wall_time_s"] for e in es]
        y = [max(e["error_force_horizontal_mean_n_per_m"], 1e-4) for e in es]
        ax.loglog(x, y, "o-", label=ladder)
        for e, xi, yi in zip(es, x, y):
            ax.annotate(e["setting"], (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=8)
        sc = [e["scatter_force_horizontal_mean_n_per_m"] for e in es]
        ax.loglog(x, sc, ":", color=ax.lines[-1].get_color(), alpha=0.6)
    ax.axhline(0.05, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("wall time per run [s]")
    ax.set_ylabel("relative error of the mean horizontal force")
    ax.set_title("Work-precision, reduced saturated cut (dotted: seed scatter)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut accuracy", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=runs.default_out("accuracy"))
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--plot-only", action="store_true")
    ap.add_argument("--coupler", help="the coupler to run (default build/bin/coupler)")
    a = ap.parse_args(argv)
    seeds = [int(s) for s in a.seeds.split(",")]
    if not a.plot_only:
        a.coupler = runs.coupler(a.coupler)
        jobs = {}
        for ladder, settings in ladders(scene_sizes(runs.effective_scene(scene(), (), a.coupler))).items():
            for label, value, sets in settings:
                for seed in seeds:
                    jobs[run_dir(a.out, ladder, label, seed)] = (sets, seed)
        # The most expensive first, so that two cores stay busy to the end.
        order = sorted(jobs, key=lambda d: ("size=0.5" not in d, "dt_safety=0.0" not in d))
        runs.side_by_side(a.jobs)
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            for d in pool.map(lambda d: run(a.coupler, d, *jobs[d]), order):
                s = read(d)
                print("%-40s %s" % (os.path.basename(d), "%.1f s" % s["wall_time_s"] if s else "FAILED"),
                      flush=True)
    rows, table = analyse(a.out, seeds)
    if not rows:
        sys.exit("rockcut accuracy: no completed runs in " + a.out)
    with open(os.path.join(a.out, "accuracy.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    text = markdown(table, seeds)
    with open(os.path.join(a.out, "accuracy.md"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "expected_error.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["ladder", "value", "force_error", "seeds"])
        w.writeheader()
        w.writerows(model_rows(a.out, table, seeds))
    with open(os.path.join(a.out, "accuracy.json"), "w") as f:
        json.dump(table, f, indent=1)
    plot(table, os.path.join(a.out, "work_precision.png"))
    print(text)
    return 0

