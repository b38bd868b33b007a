"""Error against run time of the SP pore-pressure models (DESIGN section 7).

Runs ladders of resolutions of the fluid verification scenes with both models through
`coupler run --set ...`, and writes:
  OUT/study.csv                     one row per run
  OUT/fluid_study_<case>.png        log-log error against wall time, one line per ladder and model
  OUT/fluid_study.md                the table and the observed convergence orders

  rockcut study [--out DIR] [--build DIR] [--cases terzaghi,gaussian_pulse,undrained_step]
                [--quick] [--transport inproc]
  rockcut study --time-ladder [--out DIR]   the error over the whole consolidation instead: Terzaghi
                at T_v 0.1-1 and the Gaussian pulse at D t / sigma^2 0.125-0.75, both models, both
                Laplacians (fluid.laplacian), OUT/fluid_time_ladder.{csv,md,png}

Ladders (each for `explicit` and `implicit`):
  size   particle size: finer lattices (terzaghi) or finer random packings (gaussian_pulse: windows
         of bench/data/pack57k.txt scaled to the same 40 mm domain), h / spacing fixed, the
         step a fixed fraction of h^2 / D (so space and time are refined together)
  size_h particle size at Table 1's h = 1.5 mm (h / spacing grows)
  size_sqrt  particle size with h ~ sqrt(spacing): h / spacing grows while h falls, the path on
         which SP approximations converge (both the kernel's quadrature error, a function of
         spacing / h, and its smoothing error, a function of h, vanish)
  ratio  h / spacing at a fixed particle size
  dt     the fluid step at a fixed particle size and h (the implicit model far beyond the explicit
         limit)
The error is the scene's error_l2_rel (and error_max_rel) at the final time; the wall time is the
run's wall_time_s from summary.json.
"""
import argparse
import math
import os
import sys

import numpy as np

from . import campaign, runs
from .run_data import read_summary
# The resolution ladders of each verification scene, and the constants they share with the study.
from .study_ladders import (C, CASES, D, GAUSS_DOMAIN, MODELS, gaussian_runs, terzaghi_runs,
                            undrained_runs)

ROOT = runs.REPO


def run(build, scene, sets, out_dir, transport):
    coupler = os.path.join(build, "bin", "coupler")
    sets = [f"{key}={value}" for key, value in sets.items()]
    proc = runs.run(os.path.join(ROOT, scene), out_dir, sets, coupler, transport)
    summary = read_summary(out_dir)
    if proc.returncode not in (0, 1) or summary is None:
        raise RuntimeError(f"{' '.join(runs.command(scene, out_dir, sets, coupler, transport))} "
                           f"failed ({proc.returncode}):\n{proc.stderr}")
    return summary


def order(xs, ys):
    """Least-squares slope of log y against log x."""
    if len(xs) < 2:
        return float("nan")
    return float(np.polyfit(np.log(xs), np.log(ys), 1)[0])


# The error over the whole consolidation (--time-ladder): Terzaghi at these T_v = D t / L^2 and the
# Gaussian pulse at these D t / sigma^2 (0.5: the peak has halved), both models, both Laplacians,
# at the scenes' own resolution and step.
TV_LADDER = (0.1, 0.2, 0.3, 0.5, 0.7, 1.0)
PULSE_LADDER = (0.125, 0.25, 0.5, 0.75)
TERZAGHI_L = 32.5 * 0.0006  # the scene's drainage length (ny - 1/2) spacing [m]
PULSE_SIGMA = 0.003         # the scene's pulse width [m]


def time_ladder(a):
    """Runs the time ladders and writes OUT/fluid_time_ladder.csv, .md and .png."""
    work = os.path.join(a.out, "time_ladder")
    os.makedirs(work, exist_ok=True)
    rows = []
    for case, ladder, length in (("terzaghi", TV_LADDER, TERZAGHI_L),
                                 ("gaussian_pulse", PULSE_LADDER, PULSE_SIGMA)):
        for model in MODELS:
            for laplacian in ("paper", "consistent"):
                for tv in ladder:
                    end = tv * length ** 2 / D
                    sets = {"fluid.model": f'"{model}"', "fluid.laplacian": f'"{laplacian}"',
                            "time.end_time_s": repr(end)}
                    out_dir = os.path.join(work, f"{case}_{model}_{laplacian}_{tv}")
                    s = run(a.build, CASES[case], sets, out_dir, a.transport)
                    rows.append({"case": case, "model": model, "laplacian": laplacian, "tv": tv,
                                 "end_time_s": end, "error_max_rel": float(s["error_max_rel"]),
                                 "error_l2_rel": float(s["error_l2_rel"]),
                                 "tolerance_rel": float(s["error_tolerance_rel"]),
                                 "wall_time_s": float(s["wall_time_s"])})
                    r = rows[-1]
                    print(f"{case:15s} {model:8s} {laplacian:10s} Dt/L^2={tv:<6g} max={r['error_max_rel']:.4f} "
                          f"l2={r['error_l2_rel']:.4f} wall={r['wall_time_s']:.2f}s", flush=True)
    campaign.write_rows(os.path.join(a.out, "fluid_time_ladder.csv"), rows)
    lines = ["| case | model | laplacian | D t / L^2 | error_max_rel | error_l2_rel |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['model']} | {r['laplacian']} | {r['tv']:g} | "
                     f"{r['error_max_rel']:.4f} | {r['error_l2_rel']:.4f} |")
    with open(os.path.join(a.out, "fluid_time_ladder.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, case, xlabel in ((axes[0], "terzaghi", "T_v = D t / L^2"),
                             (axes[1], "gaussian_pulse", "D t / sigma^2")):
        for model, colour in zip(MODELS, ("C0", "C1")):
            for laplacian, style in (("paper", "--"), ("consistent", "-")):
                pts = [r for r in rows if r["case"] == case and r["model"] == model
                       and r["laplacian"] == laplacian]
                ax.plot([r["tv"] for r in pts], [100 * r["error_max_rel"] for r in pts], style,
                        marker="o", color=colour, label=f"{model}, {laplacian}")
        tol = [r["tolerance_rel"] for r in rows if r["case"] == case][0]
        ax.axhline(100 * tol, color="grey", linewidth=0.8, label="scene tolerance")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("error_max_rel [%]")
        ax.set_title(case)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "fluid_time_ladder.png"), dpi=110)
    print(f"wrote {a.out}/fluid_time_ladder.csv, .md and .png")


def main(argv):
    p = argparse.ArgumentParser(prog="rockcut study", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=os.path.join(ROOT, "out", "study"))
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--cases", default="terzaghi,gaussian_pulse,undrained_step")
    p.add_argument("--quick", action="store_true", help="shorter ladders (a few minutes)")
    p.add_argument("--transport", default="inproc")
    p.add_argument("--time-ladder", action="store_true",
                   help="instead: the error over the whole consolidation (T_v ladder), both Laplacians")
    a = p.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    if a.time_ladder:
        return time_ladder(a)
    work = os.path.join(a.out, "runs")
    os.makedirs(work, exist_ok=True)

    rows = []
    for case in a.cases.split(","):
        if case == "terzaghi":
            runs = terzaghi_runs(a.quick)
        elif case == "gaussian_pulse":
            runs = gaussian_runs(a.quick, work)
        elif case == "undrained_step":
            runs = undrained_runs(a.quick)
        else:
            sys.exit(f"unknown case {case}; choose from {', '.join(CASES)}")
        for k, (ladder, model, sets) in enumerate(runs):
            out_dir = os.path.join(work, f"{case}_{k:03d}")
            s = run(a.build, CASES[case], sets, out_dir, a.transport)
            h = float(sets.get("fluid.smoothing_length_m", 0.0015))
            particles = int(s["particles"])
            if "dem.lattice.spacing_m" in sets:
                spacing = float(sets["dem.lattice.spacing_m"])
            else:  # mean spacing of the random packing: the root of the area per particle
                spacing = math.sqrt((GAUSS_DOMAIN if case == "gaussian_pulse" else 0.03) ** 2 / particles)
            row = {
                "case": case, "model": model, "ladder": ladder, "particles": particles,
                "h_m": h, "spacing_m": spacing, "dt_s": float(s["dt_s"]), "dt_over_explicit_limit": float(s["dt_s"]) / (C * h * h / D),
                "steps": int(s["steps"]), "error_l2_rel": float(s["error_l2_rel"]),
                "error_max_rel": float(s["error_max_rel"]), "wall_time_s": float(s["wall_time_s"]),
            }
            rows.append(row)
            print(f"{case:15s} {model:8s} {ladder:5s} N={particles:6d} h={h:.3e} dt={row['dt_s']:.3e} "
                  f"l2={row['error_l2_rel']:.3e} max={row['error_max_rel']:.3e} wall={row['wall_time_s']:.3f}s",
                  flush=True)

    csv_path = os.path.join(a.out, "study.csv")
    campaign.write_rows(csv_path, rows)
    plot(rows, a.out)
    report(rows, a.out)
    print(f"wrote {csv_path}, {a.out}/fluid_study_*.png, {a.out}/fluid_study.md")


def series(rows, case, model, ladder):
    return [r for r in rows if r["case"] == case and r["model"] == model and r["ladder"] == ladder]


LADDERS = (("size", "o"), ("size_h", "D"), ("size_sqrt", "v"), ("ratio", "s"), ("dt", "^"))


def refinement(r, ladder):
    """The ladder's refinement variable x (it falls as the ladder refines)."""
    if ladder.startswith("size"):
        return r["spacing_m"]
    if ladder == "ratio":
        return r["spacing_m"] / r["h_m"]
    return r["dt_s"]


def plot(rows, out):
    from .figures import plt
    for case in sorted({r["case"] for r in rows}):
        fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
        for ax, model in zip(axes, MODELS):
            for (ladder, marker), colour in zip(LADDERS, plt.rcParams["axes.prop_cycle"].by_key()["color"]):
                # In refinement order: coarse to fine along the ladder.
                pts = sorted(series(rows, case, model, ladder), key=lambda r: -refinement(r, ladder))
                if not pts:
                    continue
                ax.loglog([r["wall_time_s"] for r in pts], [r["error_l2_rel"] for r in pts], marker=marker,
                          color=colour, linestyle="-", label=f"{ladder} ladder")
            ax.set_xlabel("wall time [s]")
            ax.set_title(f"{case}, {model}")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        axes[0].set_ylabel("error_l2_rel at the final time")
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"fluid_study_{case}.png"), dpi=100)
        plt.close(fig)


def report(rows, out):
    lines = ["| case | model | ladder | particles | h [mm] | h/s | dt / explicit limit | steps | error_l2_rel | "
             "error_max_rel | wall [s] |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        ratio = f"{r['h_m'] / r['spacing_m']:.2f}"
        lines.append(f"| {r['case']} | {r['model']} | {r['ladder']} | {r['particles']} | {r['h_m'] * 1e3:.3f} | "
                     f"{ratio} | {r['dt_over_explicit_limit']:.3g} | {r['steps']} | {r['error_l2_rel']:.3e} | "
                     f"{r['error_max_rel']:.3e} | {r['wall_time_s']:.3f} |")
    lines += ["", "Observed orders p, error_l2_rel ~ x^p, with x the ladder's refinement variable (it falls as "
              "the ladder refines): the spacing s for the size ladders, s / h for `ratio`, dt for `dt`. p is the "
              "least-squares slope in log-log; the local orders between consecutive rungs follow it. Positive: "
              "the error falls with refinement.", "",
              "| case | model | ladder | x | p (fit) | local orders |", "|---|---|---|---|---|---|"]
    for case in sorted({r["case"] for r in rows}):
        for model in MODELS:
            for ladder, _ in LADDERS:
                pts = series(rows, case, model, ladder)
                if len(pts) < 2:
                    continue
                xs = [refinement(r, ladder) for r in pts]
                var = "s" if ladder.startswith("size") else ("s / h" if ladder == "ratio" else "dt")
                pairs = sorted(zip(xs, [r["error_l2_rel"] for r in pts]))
                local = [math.log(e1 / e0) / math.log(x1 / x0) for (x0, e0), (x1, e1) in zip(pairs, pairs[1:])]
                lines.append(f"| {case} | {model} | {ladder} | {var} | {order(*zip(*pairs)):.2f} | "
                             f"{', '.join(f'{v:.2f}' for v in local)} |")
    with open(os.path.join(out, "fluid_study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")

