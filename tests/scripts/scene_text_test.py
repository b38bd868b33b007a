#!/usr/bin/python3
"""scripts/scene_text.py: the plain-text look into a scene that sweep, accuracy and plot_cutting
use for a field or two (dem.threads, the size ladder's radii and strengths, the tool's geometry).

  tests/scripts/scene_text_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
import sys
import unittest

import harness  # tests/scripts/harness.py: the command line

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import scene_text  # noqa: E402

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
        # The size ladder's strengths come from the scene, so they follow a change of its rock.
        import accuracy  # noqa: E402  (its command line is read in main() only)
        with open(accuracy.SCENE) as f:
            bonds = scene_text.scalar_fields(f.read(), "bonds")
        sets = dict(s.split("=") for s in accuracy.size_sets(0.5))
        self.assertAlmostEqual(float(sets["dem.bonds.tensile_strength_n_per_m"]),
                               0.5 * bonds["tensile_strength_n_per_m"])
        self.assertAlmostEqual(float(sets["dem.bonds.shear_strength_n_per_m"]),
                               0.5 * bonds["shear_strength_n_per_m"])


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
