#!/usr/bin/python3
"""The analytical cutting models on the figures (python/rockcut/plot.py, sweep_figures.py): the
force figure of a real small dry cut draws each model's horizontal force from summary.json's
analytical_* keys, and the sweep's force figure draws each model's value per water depth beside
the DEM points. Both must read the values, never compute them: the tests plant distinctive values
in the summaries and look for exactly those on the axes.

  tests/python/analytical_figures_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import unittest
from unittest import mock

import harness  # tests/python/harness.py: the command line

import matplotlib

matplotlib.use("Agg")
from matplotlib.axes import Axes  # noqa: E402

from rockcut import plot, sweep_figures  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(ROOT, "cases", "cutting", "dry_reduced.pbtxt")
# tests/integration/cutting_test.cpp's small cut: about 150 discs, 7 mm of travel, about a second.
SMALL_CUT = ["--set", "dem.specimen.radius_min_m=0.0016", "--set", "dem.specimen.radius_max_m=0.0032",
             "--set", "time.end_time_s=0.008", "--set", "dem.tool.steady_after_m=0.004",
             "--set", "output.frame_interval_s=0.002"]
ARGS = None
# Planted values [N/m]: no model gives them for this scene, so finding them on the axes shows the
# figure read summary.json.
PLANTED = {"evans": 111111.0, "nishimatsu": 22222.0, "merchant": 333333.0, "hyperbaric": 444444.0}


class ForceFigureOfACut(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "analytical_force_figure")
        shutil.rmtree(cls.out, ignore_errors=True)
        r = subprocess.run([ARGS.coupler, "run", CASE, "--out", cls.out, *SMALL_CUT],
                           capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        path = os.path.join(cls.out, "summary.json")
        with open(path) as f:
            cls.summary = json.load(f)
        for stem, value in PLANTED.items():
            cls.summary[f"analytical_{stem}_force_horizontal_n_per_m"] = value
        with open(path, "w") as f:
            json.dump(cls.summary, f)

    def test_the_run_carries_every_model(self):
        for stem, _, _ in plot.ANALYTICAL_MODELS:
            self.assertIn(f"analytical_{stem}_force_horizontal_n_per_m", self.summary)

    def test_each_model_is_a_horizontal_line_of_its_summary_value(self):
        lines = []
        original = Axes.axhline

        def record(ax, y=0, *args, **kwargs):
            lines.append((y, kwargs.get("label", "")))
            return original(ax, y, *args, **kwargs)

        with mock.patch.object(Axes, "axhline", record):
            plot.plot_cutting(self.out)
        self.assertTrue(os.path.exists(os.path.join(self.out, "force.png")))
        for (stem, label, _), (planted_stem, value) in zip(plot.ANALYTICAL_MODELS, PLANTED.items()):
            self.assertEqual(stem, planted_stem)
            drawn = [y for y, text in lines if text.startswith(label)]
            self.assertEqual(len(drawn), 1, f"{label}: {lines}")
            self.assertAlmostEqual(drawn[0], value / 1e3, places=9)

    def test_a_summary_without_models_draws_none(self):
        self.assertEqual(plot.analytical_lines({"force_horizontal_mean_n_per_m": 1.0}), [])
        # A model without a value (null in summary.json: no shear plane) is left out.
        self.assertEqual(plot.analytical_lines({"analytical_merchant_force_horizontal_n_per_m": None}),
                         [])


class SweepForceFigure(unittest.TestCase):
    def test_models_are_drawn_per_depth_beside_the_dem_points(self):
        out = os.path.join(ARGS.tmp, "analytical_sweep_figure")
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        rows = []
        for depth in (0, 100, 1000):
            for seed in (1, 2):
                row = {"water_depth_m": depth, "seed": seed, "exit_code": 0,
                       "hydrostatic_pressure_pa": 101325.0 + 1025 * 9.81 * depth,
                       "force_horizontal_mean_n_per_m": 1e5 + depth + seed,
                       "force_horizontal_peak_n_per_m": 3e5 + depth,
                       "force_vertical_mean_n_per_m": 1e4}
                for stem, value in PLANTED.items():
                    row[f"analytical_{stem}_force_horizontal_n_per_m"] = value + depth
                rows.append(row)
        drawn = {}
        original = sweep_figures.plot_series

        def record(ax, x, y, fmt, **kwargs):
            if "label" in kwargs:
                drawn[kwargs["label"]] = list(y)
            return original(ax, x, y, fmt, **kwargs)

        with mock.patch.object(sweep_figures, "plot_series", record):
            sweep_figures.fig_forces(sweep_figures.Sweep(out, "water_depth_m", rows))
        self.assertTrue(os.path.exists(os.path.join(out, "fig08_forces.png")))
        for stem, label, _ in plot.ANALYTICAL_MODELS:
            self.assertIn(label, drawn)
            expected = [(PLANTED[stem] + depth) / 1e3 for depth in (0, 100, 1000)]
            for got, want in zip(drawn[label], expected):
                self.assertAlmostEqual(got, want, places=9)
        self.assertIn("horizontal mean (resisting the cut)", drawn)
        self.assertEqual(drawn["horizontal peak"], [300.0, 300.1, 301.0])


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
