#!/usr/bin/python3
"""coupler/data/expected_error.csv, the table the coupler's start-up estimate reads, is the accuracy
studies' output: its errors are recomputed here from the studies' committed runs. Local damping
(the mean force): docs/accuracy/accuracy.csv (dt_safety, h, size and N = 14) and
docs/accuracy/interval_0000m.csv (the paired differences of N = 10 ... 2). Dashpots (the peak
force): docs/accuracy/viscous/accuracy.csv (dt_safety, h, size) and
docs/accuracy/viscous/interval_0000m.csv (the paired difference of N = 3 over sixteen seeds) and,
for the fluid's force extrapolated between exchanges, interval_extrapolated_0000m.csv (N = 4), and
with the lag's energy taken out, interval_passivity_0000m.csv (N = 8).
And rockcut accuracy writes a table of the same form.

  tests/python/expected_error_table_test.py --coupler build/bin/coupler --tmp DIR
"""
import collections
import csv
import json
import os
import shutil
import unittest

import harness  # tests/python/harness.py: the command line
from rockcut import accuracy, runs
from rockcut.stats import mean, paired_table

TABLE = os.path.join(runs.REPO, "coupler", "data", "expected_error.csv")
DOCS = os.path.join(runs.REPO, "docs", "accuracy")
ARGS = None


def read_table(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def study_errors(test, rows_of, study_csv, key, paired=None):
    """Checks the dt_safety, h and size rows of one damping's table against its study's runs, but
    for the (ladder, setting) -> error pairs in `paired` (measured over more seeds); returns
    error(ladder, setting) of those runs."""
    by = collections.defaultdict(list)
    for r in harness.read_csv(study_csv):
        by[(r["ladder"], r["setting"])].append(float(r[key]))
    finest = {"dt_safety": "0.025", "N": "1", "h": "1.67", "size": "0.5"}

    def error(ladder, setting):
        ref = mean(by[(ladder, finest[ladder])])
        return abs(mean(by[(ladder, setting)]) - ref) / abs(ref)

    for ladder, model in (("dt_safety", "dt_safety"), ("h", "h_per_diameter"),
                          ("size", "size_scale")):
        table = rows_of(model)
        settings = sorted({s for (l, s) in by if l == ladder}, key=float, reverse=True)
        test.assertEqual([v for v, _ in table], [float(s) for s in settings], model)
        for (value, e), setting in zip(table, settings):
            want = (paired or {}).get((ladder, setting))
            want = error(ladder, setting) if want is None else want
            test.assertAlmostEqual(e, want, delta=5e-5, msg=(model, setting))
    return error


class TableIsTheStudys(unittest.TestCase):
    def setUp(self):
        self.rows = read_table(TABLE)

    def errors(self, ladder, damping="local", fluid_force="held"):
        return [(float(r["value"]), float(r["force_error"])) for r in self.rows
                if r["ladder"] == ladder and r.get("damping", "local") == damping
                and r.get("fluid_force", "held") == fluid_force]

    def test_each_damping_reads_its_own_force(self):
        forces = {(r["damping"], r["force"]) for r in self.rows}
        self.assertEqual(forces, {("local", "mean"), ("viscous", "peak")})

    def test_ladders_from_the_accuracy_study(self):
        error = study_errors(self, self.errors, os.path.join(DOCS, "accuracy.csv"),
                             "force_horizontal_mean_n_per_m")
        # The coarsest N (14) of the fluid-step ladder, placed at the limit itself (1).
        self.assertEqual(self.errors("fluid_step_ratio")[0][0], 1.0)
        self.assertAlmostEqual(self.errors("fluid_step_ratio")[0][1], error("N", "14"), delta=5e-5)

    def test_coupling_interval_from_the_paired_study_over_sixteen_seeds(self):
        rows = harness.read_csv(os.path.join(DOCS, "interval_0000m.csv"))
        paired = {int(v): rel for v, _, _, _, _, _, rel, _ in
                  paired_table(rows, "force_horizontal_mean_n_per_m")}
        table = self.errors("fluid_step_ratio")[1:]
        self.assertEqual(len(table), len(paired))
        for (value, e), n in zip(table, sorted(paired, reverse=True)):
            self.assertAlmostEqual(value, round(0.0705 * n, 4), delta=6e-4, msg=n)
            self.assertAlmostEqual(e, abs(paired[n]), delta=5e-5, msg=n)

    def test_dashpots_from_their_study_and_sixteen_seeds(self):
        # The default step, dt_safety 0.2, against 0.05 seed by seed over sixteen seeds.
        dt = paired_table(harness.read_csv(os.path.join(DOCS, "viscous", "dt_safety_0000m.csv")),
                          "force_horizontal_peak_n_per_m")
        self.assertEqual([v for v, *_ in dt], [0.05, 0.2])
        self.assertEqual(dt[1][1], 16)
        study_errors(self, lambda model: self.errors(model, "viscous"),
                     os.path.join(DOCS, "viscous", "accuracy.csv"), "force_horizontal_peak_n_per_m",
                     paired={("dt_safety", "0.2"): abs(dt[1][6])})
        rows = harness.read_csv(os.path.join(DOCS, "viscous", "interval_0000m.csv"))
        paired = {int(v): rel for v, _, _, _, _, _, rel, _ in
                  paired_table(rows, "force_horizontal_peak_n_per_m")}
        # N = 3, the largest the limit allows, placed at the limit itself; N = 1 has no lag. (N = 10
        # lies beyond the limit: not a setting the coupler runs.)
        self.assertEqual(self.errors("fluid_step_ratio", "viscous")[0],
                         (1.0, round(abs(paired[3]), 4)))
        self.assertEqual(self.errors("fluid_step_ratio", "viscous")[-1][1], 0.0)
        self.assertEqual(len(self.errors("fluid_step_ratio", "viscous")), 2)

    def check_lag_ladder(self, study_csv, n, fluid_force, n1_ratio):
        """The table's lag ladder for `fluid_force`: N = n, the largest its limit allows, placed at
        the limit itself, with its sixteen-seed paired error; N = 1 (no lag) at n1_ratio."""
        rows = harness.read_csv(os.path.join(DOCS, "viscous", study_csv))
        paired = {int(v): (runs_, rel) for v, runs_, _, _, _, _, rel, _ in
                  paired_table(rows, "force_horizontal_peak_n_per_m")}
        self.assertEqual(paired[n][0], 16)
        ladder = self.errors("fluid_step_ratio", "viscous", fluid_force)
        self.assertEqual(ladder[0], (1.0, round(abs(paired[n][1]), 4)))
        self.assertEqual(ladder[-1], (n1_ratio, 0.0))
        self.assertEqual(len(ladder), 2)
        # Only the lag's ladder depends on how the force is applied.
        for other in ("dt_safety", "h_per_diameter", "size_scale"):
            self.assertEqual(self.errors(other, "viscous", fluid_force), [], other)

    def test_the_extrapolated_force_from_its_sixteen_seeds(self):
        # N = 4 at 0.803 of the extrapolated force's limit.
        self.check_lag_ladder("interval_extrapolated_0000m.csv", 4, "extrapolated", 0.2008)

    def test_the_lags_energy_taken_out_from_its_sixteen_seeds(self):
        # N = 8 at 0.973 of that limit times 1.65 (coupler/run/time_plan.hpp).
        self.check_lag_ladder("interval_passivity_0000m.csv", 8, "extrapolated+passivity", 0.1217)


class AccuracyWritesTheTable(unittest.TestCase):
    def test_expected_error_csv_from_a_study_folder(self):
        # A study folder with two seeds per setting, made up: Fh = 100 at every finest setting,
        # 110 and 130 elsewhere (errors 0.1 and 0.3), and a start-up report giving dt / the
        # stiffness limit = 0.05.
        out = os.path.join(ARGS.tmp, "accuracy_table")
        shutil.rmtree(out, ignore_errors=True)
        seeds = [1, 2]
        ladders = accuracy.ladders(None)
        for ladder, settings in ladders.items():
            for k, (label, _, _) in enumerate(settings):
                fh = 100.0 if k == len(settings) - 1 else (110.0 if k % 2 else 130.0)
                for seed in seeds:
                    d = accuracy.run_dir(out, ladder, label, seed)
                    os.makedirs(d, exist_ok=True)
                    summary = {"status": "completed", "wall_time_s": 1.0, "coupling_interval": 1,
                               "particles": 10, "breaks_tensile": 1, "breaks_shear": 1}
                    for key in accuracy.KEYS:
                        summary[key] = fh
                    with open(os.path.join(d, "summary.json"), "w") as f:
                        json.dump(summary, f)
        with open(os.path.join(accuracy.run_dir(out, "N", "1", 1), "log.txt"), "w") as f:
            f.write("limit  fluid_module pore_fluid_stiffness: dt <= 2e-06 s (lagged)\n"
                    "chosen dt = 1e-07 s (binding: dem_module dem_springs x dt_safety 0.2)\n")
        self.assertEqual(accuracy.main(["--plot-only", "--out", out, "--seeds", "1,2"]), 0)
        rows = read_table(os.path.join(out, "expected_error.csv"))
        n = [(float(r["value"]), float(r["force_error"])) for r in rows
             if r["ladder"] == "fluid_step_ratio"]
        # N = 14, 7, 3, 1; N = 3 is the default setting, whose runs every ladder shares (the last
        # written above, size's second setting, has Fh = 110).
        self.assertEqual(n, [(0.7, 0.3), (0.35, 0.1), (0.15, 0.1), (0.05, 0.0)])
        dt = [(r["value"], float(r["force_error"])) for r in rows if r["ladder"] == "dt_safety"]
        self.assertEqual(dt, [("0.4", 0.3), ("0.2", 0.1), ("0.1", 0.3), ("0.05", 0.1),
                              ("0.025", 0.0)])
        self.assertEqual({r["seeds"] for r in rows}, {"2"})


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
