#!/usr/bin/python3
"""rockcut.run_data's plain-text look into a scene that sweep, accuracy and plot use for a field
or two (dem.threads, the size ladder's radii and strengths, the tool's geometry), on the effective
scene (runs.effective_scene: the bases merged).

  tests/python/scene_fields_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
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
        effective = runs.effective_scene(accuracy.scene(), (), ARGS.coupler)
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

    def test_walls_of_the_effective_scene(self):
        # What rockcut animate draws: the reduced cut's floor and side walls (as written in
        # cases/cutting/dry_reduced.pbtxt), and the closed box of initial_overlaps.
        walls = scene_text.scene_walls(
            runs.effective_scene(runs.case("cutting", "saturated_reduced.pbtxt"), (), ARGS.coupler))
        self.assertEqual([w["name"] for w in walls], ["floor", "right", "left"])
        self.assertEqual(walls[0]["vertices"].tolist(), [[-0.05, 0.0], [0.15, 0.0]])
        self.assertEqual(walls[2]["vertices"].tolist(), [[0.0, 0.0], [0.0, 0.015]])
        self.assertFalse(walls[0]["closed"])
        self.assertEqual(walls[1]["velocity_m_s"].tolist(), [0.0, 0.0])
        box = scene_text.scene_walls('dem { walls { name: "box" closed: true velocity_m_s { y: -0.5 }'
                                     ' vertex_m { x: 1 } vertex_m { x: 1 y: 2 } vertex_m { y: 2 } } }')
        self.assertEqual(len(box), 1)
        self.assertTrue(box[0]["closed"])
        self.assertEqual(box[0]["vertices"].tolist(), [[1.0, 0.0], [1.0, 2.0], [0.0, 2.0]])
        self.assertEqual(box[0]["velocity_m_s"].tolist(), [0.0, -0.5])

    def test_runs_side_by_side_follow_the_dem_threads_of_the_effective_scene(self):
        dry = runs.case("cutting", "dry.pbtxt")  # dem { threads: 2 }, its rock from a base
        self.assertEqual(runs.dem_threads(dry, (), ARGS.coupler), 2)
        self.assertEqual(runs.dem_threads(dry, ["dem.threads=3"], ARGS.coupler), 3)
        self.assertEqual(runs.dem_threads(runs.case("cutting", "dry_reduced.pbtxt"), (),
                                          ARGS.coupler), 1)  # the default
        self.assertEqual(runs.default_jobs(dry, ["dem.threads=1"], ARGS.coupler),
                         runs.cpu_count())

    def test_runs_side_by_side_neither_poll_nor_spin(self):
        # Several runs on the same cores: no polling for replies, OpenMP threads that sleep (the
        # coupler lets a dry run's DEM spin when it has the cores to itself).
        keys = ("ROCKCUT_WIRE_SPIN_US", "OMP_WAIT_POLICY", "GOMP_SPINCOUNT")
        saved = {k: os.environ.pop(k, None) for k in keys}
        try:
            runs.side_by_side(1)
            self.assertFalse(any(k in os.environ for k in keys))
            runs.side_by_side(2)
            self.assertEqual(os.environ["ROCKCUT_WIRE_SPIN_US"], "0")
            self.assertEqual(os.environ["OMP_WAIT_POLICY"], "PASSIVE")
            for k in keys:
                os.environ.pop(k, None)
            os.environ["GOMP_SPINCOUNT"] = "1000"  # the user's own choice wins
            runs.side_by_side(2)
            self.assertNotIn("OMP_WAIT_POLICY", os.environ)
        finally:
            for k, v in saved.items():
                os.environ.pop(k, None)
                if v is not None:
                    os.environ[k] = v

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
