"""Work-precision study of coupled cutting (docs/record/accuracy.md): error against wall time.

  rockcut accuracy [--damping local|viscous] [--jobs N] [--out DIR] [--seeds 1,2,3,4]
                   [--plot-only] [--coupler PATH]

One study per damping model, each on its scene and for the force that model's cut is read by:
  local    cases/cutting/saturated_reduced.pbtxt cut short to 24 mm (steady from 10 mm), the mean
           horizontal force;
  viscous  cases/cutting/saturated_reduced_long_viscous.pbtxt with the fluid's force held between
           exchanges at N = 3 (coupling.fluid_force held, lag_correction none,
           interval_fraction 1), the first 39 mm (steady from 10 mm), the peak horizontal force
           (under dashpots the mean is mostly the zeros between chips: docs/model.md). The scene's
           own coupling (extrapolated, the lag's energy taken out, N = 8) is measured against
           N = 1 over sixteen seeds (docs/record/accuracy.md).
Four ladders vary one setting each from the defaults:
  dt_safety   time.dt_safety        0.4, 0.2 (default), 0.1, 0.05, 0.025
  N           coupling.interval     local: 14 (the largest the limits allow), 7, 3 (the coupler's
                                    choice, coupling.interval_fraction 0.25 of the largest), 1 (no
                                    lag); viscous: 3 (the largest the limit allows), 1
  h           fluid.smoothing_length_m / mean diameter   1.67, 2.5 (default), 3.33
  size        disc radii x 1.5, 1 (default), 0.75, 0.5, with the bond strengths and h scaled alike
              (a 2D bond's strength acts over about one diameter: see the scene's header)
Every setting runs once per seed. The error of a setting is |mean over seeds - that of the ladder's
finest setting| / |finest|, for the mean and peak horizontal force, the mean vertical force, the
bond breaks and the node pressures P1-P3, beside the seed scatter (standard error of the mean).

Writes DIR/accuracy.csv (one row per run), DIR/accuracy.md (the table), DIR/work_precision.png
(error of the study's force against wall time, log-log, one line per ladder) and
DIR/expected_error.csv, the error of the study's force per ladder setting in the variables of the
coupler's start-up estimate (coupler/data/expected_error.csv has this form): dt_safety,
fluid_step_ratio (N dt / the pore_fluid_stiffness limit, from the runs' start-up reports),
h_per_diameter and size_scale, with the damping model and the force (mean or peak) on each row.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import sys

from . import runs
from .accuracy_report import markdown, plot
from .run_data import read_summary, scalar_fields
from .stats import mean, sem

# Each damping model's study: its scene, its length, the force it is read by, its N ladder and the
# coupler's own N there (the setting every ladder shares).
STUDIES = {
    "local": {"scene": "saturated_reduced.pbtxt", "end_time_s": 0.025,
              "force": "mean", "N": (14, 7, 3, 1), "default_N": 3},
    "viscous": {"scene": "saturated_reduced_long_viscous.pbtxt",
                "end_time_s": 0.04, "force": "peak", "N": (3, 1), "default_N": 3,
                # Run held at N = 3 (half the wall of N = 1); the N ladder gives the held lag.
                "sets": ["coupling.fluid_force=held", "coupling.lag_correction=none",
                         "coupling.interval_fraction=1"]},
}
DAMPING = "local"
STUDY = STUDIES[DAMPING]


def use(damping):
    """Makes `damping`'s study the one this module's functions run and read."""
    global DAMPING, STUDY
    DAMPING, STUDY = damping, STUDIES[damping]


def scene():
    """The study's scene: a saturated reduced cut."""
    return runs.case("cutting", STUDY["scene"])


def base():
    return ["time.end_time_s=%g" % STUDY["end_time_s"], "dem.tool.steady_after_m=0.01",
            "output.frame_interval_s=0"] + STUDY.get("sets", [])


def force_key():
    """The summary key of the force the study measures."""
    return "force_horizontal_%s_n_per_m" % STUDY["force"]


KEYS = ["force_horizontal_mean_n_per_m", "force_horizontal_peak_n_per_m",
        "force_vertical_mean_n_per_m", "breaks", "pressure_p1_mean_pa", "pressure_p2_mean_pa",
        "pressure_p3_mean_pa"]


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
    "N": [(str(n), n, [] if n == STUDY["default_N"] else ["coupling.interval=%d" % n])
          for n in STUDY["N"]],
    "h": [("3.33", 3.33, ["fluid.smoothing_length_m=0.008"]), ("2.5", 2.5, []),
          ("1.67", 1.67, ["fluid.smoothing_length_m=0.004"])],
    "size": [("1.5", 1.5, size_sets(1.5, sizes)), ("1", 1.0, []),
             ("0.75", 0.75, size_sets(0.75, sizes)), ("0.5", 0.5, size_sets(0.5, sizes))],
    }


LADDER_NAMES = ("dt_safety", "N", "h", "size")


def default_label(ladder):
    return {"dt_safety": "0.2", "N": str(STUDY["default_N"]), "h": "2.5", "size": "1"}[ladder]


def run_dir(out, ladder, label, seed):
    # The default setting is shared by all ladders: run once.
    if default_label(ladder) == label:
        return os.path.join(out, "default_seed%d" % seed)
    return os.path.join(out, "%s=%s_seed%d" % (ladder, label, seed))


def run(coupler, out_dir, sets, seed):
    if os.path.exists(os.path.join(out_dir, "summary.json")):
        return out_dir
    os.makedirs(out_dir, exist_ok=True)
    runs.run(scene(), out_dir, base() + sets + ["dem.specimen.seed=%d" % seed], coupler,
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
    """The rows of expected_error.csv: ladder (the model's variable), value, force_error, seeds,
    damping, force."""
    rows = []
    per_n = fluid_step_per_interval(os.path.join(run_dir(out, "N", "1", seeds[0]), "log.txt"))
    for e in table:
        if e.get("missing"):
            continue
        value = e["value"]
        if e["ladder"] == "N":
            if per_n is None:
                continue  # no start-up report to place N against the limit
            # The largest N the limit allows is written as the limit itself, so that every
            # stable N is covered.
            value = 1.0 if (value + 1) * per_n > 1 else value * per_n
        rows.append({"ladder": MODEL_LADDERS[e["ladder"]], "value": "%.4g" % value,
                     "force_error": "%.4f" % e["error_" + force_key()],
                     "seeds": e["runs"], "damping": DAMPING, "force": STUDY["force"]})
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


def main(argv):
    ap = argparse.ArgumentParser(prog="rockcut accuracy", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--damping", choices=sorted(STUDIES), default="local",
                    help="the study: the paper's local damping or dashpots (default local)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=runs.default_out("accuracy"))
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--plot-only", action="store_true")
    ap.add_argument("--coupler", help="the coupler to run (default build/bin/coupler)")
    a = ap.parse_args(argv)
    seeds = [int(s) for s in a.seeds.split(",")]
    use(a.damping)
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
    text = markdown(table, seeds, KEYS)
    with open(os.path.join(a.out, "accuracy.md"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "expected_error.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["ladder", "value", "force_error", "seeds", "damping",
                                          "force"])
        w.writeheader()
        w.writerows(model_rows(a.out, table, seeds))
    with open(os.path.join(a.out, "accuracy.json"), "w") as f:
        json.dump(table, f, indent=1)
    plot(table, os.path.join(a.out, "work_precision.png"), LADDER_NAMES, STUDY["force"])
    print(text)
    return 0

