#!/usr/bin/python3
"""rockcut.run_data's plain-text look into a scene that sweep, accuracy and plot use for a field
or two (dem.threads, the size ladder's radii and strengths, the tool's geometry), on the effective
scene (runs.effective_scene: the bases merged).

  tests/python/scene_fields_test.py --coupler build/bin/coupler --tmp DIR
"""
import unittest

import harness  # tests/python/harness.py: the command line
from rockcut import accuracy, runs
from rockcut import run_data as scene_text

TEXT = """
dem {
  threads: 2  # threads: 7 in a comment does not count
  specimen { radius_min_m: 8e-4 radius_max_m: 1.6E-3 seed: 3 }
  bonds {
    tensile_strength_n_per_m: 2.66e4
    shear_strength_n_per_m: -1.5e+2
  }
  local_damping: 0.7
}
# fluid { smoothing_length_m: 9 }
fluid: { smoothing_length_m: 0.006 model: EXPLICIT }
"""


class ScalarFields(unittest.TestCase):
    def test_own_fields_only_without_the_nested_blocks(self):
        self.assertEqual(scene_text.scalar_fields(TEXT, "dem"), {"threads": 2.0, "local_damping": 0.7})

    def test_exponents_signs_and_both_block_spellings(self):
        self.assertEqual(scene_text.scalar_fields(TEXT, "specimen"),
                         {"radius_min_m": 8e-4, "radius_max_m": 1.6e-3, "seed": 3.0})
        self.assertEqual(scene_text.scalar_fields(TEXT, "bonds"),
                         {"tensile_strength_n_per_m": 2.66e4, "shear_strength_n_per_m": -150.0})
        # the commented-out block is skipped, `fluid: {` is found, an enum is not a number
        self.assertEqual(scene_text.scalar_fields(TEXT, "fluid"), {"smoothing_length_m": 0.006})

    def test_a_missing_block_gives_no_fields(self):
        self.assertEqual(scene_text.scalar_fields(TEXT, "tool"), {})
        self.assertEqual(scene_text.scalar_fields("", "dem"), {})

    def test_the_accuracy_study_scales_the_scene_it_runs(self):
        # The size ladder's strengths come from the effective scene, so they follow a change of
        # its rock, which lives in a base (cases/rock/default_rock_coarse.pbtxt).
        effective = runs.effective_scene(accuracy.SCENE, (), ARGS.coupler)
        with open(runs.case("rock", "default_rock_coarse.pbtxt")) as f:
            rock = scene_text.scalar_fields(f.read(), "bonds")
        self.assertEqual(scene_text.scalar_fields(effective, "bonds")["tensile_strength_n_per_m"],
                         rock["tensile_strength_n_per_m"])
        sets = dict(s.split("=") for s in accuracy.size_sets(0.5, accuracy.scene_sizes(effective)))
        self.assertAlmostEqual(float(sets["dem.bonds.tensile_strength_n_per_m"]),
                               0.5 * rock["tensile_strength_n_per_m"])
        self.assertAlmostEqual(float(sets["dem.bonds.shear_strength_n_per_m"]),
                               0.5 * rock["shear_strength_n_per_m"])
        self.assertAlmostEqual(float(sets["fluid.smoothing_length_m"]), 0.003)

    def test_runs_side_by_side_follow_the_dem_threads_of_the_effective_scene(self):
        dry = runs.case("cutting", "dry.pbtxt")  # dem { threads: 2 }, its rock from a base
        self.assertEqual(runs.dem_threads(dry, (), ARGS.coupler), 2)
        self.assertEqual(runs.dem_threads(dry, ["dem.threads=3"], ARGS.coupler), 3)
        self.assertEqual(runs.dem_threads(runs.case("cutting", "dry_reduced.pbtxt"), (),
                                          ARGS.coupler), 1)  # the default
        self.assertEqual(runs.default_jobs(dry, ["dem.threads=1"], ARGS.coupler),
                         runs.cpu_count())

    def test_effective_scene_applies_overrides_and_refuses_a_bad_scene(self):
        text = runs.effective_scene(runs.case("cutting", "dry_reduced.pbtxt"), ["dem.threads=3"],
                                    ARGS.coupler)
        self.assertEqual(scene_text.scalar_fields(text, "dem").get("threads"), 3.0)
        self.assertNotIn("base:", text)
        with self.assertRaises(SystemExit) as e:
            runs.effective_scene(runs.case("cutting", "dry_reduced.pbtxt"), ["dem.nope=1"],
                                 ARGS.coupler)
        self.assertIn("nope", str(e.exception))


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
