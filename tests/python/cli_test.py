#!/usr/bin/python3
"""The rockcut command line: scripts/rockcut and python3 -m rockcut list the same verbs, every
verb's module imports and answers --help, an unknown verb is refused with the nearest name, and
rockcut plot draws a calibration run's stress-strain curve (a run.h5 written here).

  tests/python/cli_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import subprocess
import unittest

import h5py
import numpy as np

import harness  # tests/python/harness.py: the command line
from rockcut import runs
from rockcut.__main__ import VERBS

ROCKCUT = os.path.join(runs.REPO, "scripts", "rockcut")
ARGS = None


def rockcut(*args, module=False):
    argv = ["/usr/bin/python3", "-m", "rockcut", *args] if module else [ROCKCUT, *args]
    return subprocess.run(argv, capture_output=True, text=True, timeout=60)


class CommandLine(unittest.TestCase):
    def test_help_lists_every_verb_both_ways(self):
        r = rockcut("--help")
        self.assertEqual(r.returncode, 0, r.stderr)
        for verb in ("sweep", "status", "collect", "windows", "compare", "paired", "plot",
                     "animate", "calibrate", "accuracy", "extreme", "regression", "study",
                     "crop-packing"):
            self.assertRegex(r.stdout, rf"\n  {verb} +\S", verb)
        self.assertEqual(rockcut("--help", module=True).stdout, r.stdout)  # PYTHONPATH from ctest

    def test_every_verb_answers_help(self):
        for verb in VERBS:
            r = rockcut(verb, "--help")
            self.assertEqual(r.returncode, 0, f"{verb}: {r.stderr}")
            self.assertIn(f"rockcut {verb}", r.stdout, verb)

    def test_an_unknown_verb_is_refused_with_the_nearest(self):
        r = rockcut("swep")
        self.assertEqual(r.returncode, 2)
        self.assertIn("no verb 'swep'; did you mean 'sweep'?", r.stderr)
        self.assertEqual(rockcut().returncode, 2)

    def test_plot_draws_a_calibration_run(self):
        out = os.path.join(ARGS.tmp, "cli_calibration")
        os.makedirs(out, exist_ok=True)
        strain = np.linspace(0.0, 3e-3, 50)
        with h5py.File(os.path.join(out, "run.h5"), "w") as f:
            f["timeseries/axial_strain"] = strain
            f["timeseries/axial_stress_pa"] = 5.5e9 * strain
        with open(os.path.join(out, "summary.json"), "w") as f:
            json.dump({"title": "UCS", "ucs_pa": 1.4e7, "youngs_modulus_pa": 5.5e9,
                       "poisson_ratio": 0.2}, f)
        png = os.path.join(out, "stress_strain.png")
        if os.path.exists(png):
            os.remove(png)
        r = rockcut("plot", out)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertGreater(os.path.getsize(png), 1000)

    def test_plot_draws_a_fracture_test_as_pull_against_elongation(self):
        out = os.path.join(ARGS.tmp, "cli_fracture")
        os.makedirs(out, exist_ok=True)
        elongation = np.linspace(0.0, 3e-5, 50)
        with h5py.File(os.path.join(out, "run.h5"), "w") as f:
            f["timeseries/axial_strain"] = -elongation / 0.02
            f["timeseries/elongation_m"] = elongation
            f["timeseries/pulling_force_n_per_m"] = np.minimum(7e9 * elongation, 1e5)
        with open(os.path.join(out, "summary.json"), "w") as f:
            json.dump({"title": "fracture", "fracture_energy_j_per_m2": 44.0,
                       "net_tensile_strength_pa": 5.1e6}, f)
        for name in ("force_elongation.png", "stress_strain.png"):
            if os.path.exists(os.path.join(out, name)):
                os.remove(os.path.join(out, name))
        r = rockcut("plot", out)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertGreater(os.path.getsize(os.path.join(out, "force_elongation.png")), 1000)
        self.assertFalse(os.path.exists(os.path.join(out, "stress_strain.png")))


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
