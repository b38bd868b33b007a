#!/usr/bin/python3
"""`cmake --install` as a cluster's software module, a container or a package recipe does it:
installs the build into a temporary prefix, then runs the installed programs from a directory
outside the source and build trees, on the installed example scenes. About 10 s.

  tests/install/install_test.py --build BUILD_DIR --tmp DIR
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import unittest

ARGS = None
PROGRAMS = ("coupler", "dem_module", "fluid_module", "scene_reference")


class Installed(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.root = os.path.join(ARGS.tmp, "install")
        shutil.rmtree(cls.root, ignore_errors=True)
        cls.prefix = os.path.join(cls.root, "prefix")
        cls.install = subprocess.run(["cmake", "--install", ARGS.build, "--prefix", cls.prefix],
                                     capture_output=True, text=True, timeout=300)
        cls.work = os.path.join(cls.root, "work")  # the user's directory: no cases/, no build/
        os.makedirs(cls.work)
        cls.bin = os.path.join(cls.prefix, "bin")
        cls.share = os.path.join(cls.prefix, "share", "rockcut")

    def run_here(self, argv, path=None, timeout=120):
        env = dict(os.environ)
        if path is not None:
            env["PATH"] = path
        return subprocess.run(argv, capture_output=True, text=True, timeout=timeout,
                              cwd=self.work, env=env)

    def test_install_puts_programs_data_cases_and_docs_in_the_prefix(self):
        self.assertEqual(self.install.returncode, 0, self.install.stdout + self.install.stderr)
        for program in PROGRAMS:
            self.assertTrue(os.access(os.path.join(self.bin, program), os.X_OK), program)
        for data in ("expected_error.csv", "scene_descriptor.pb", "cases/cutting/dry_reduced.pbtxt",
                     "cases/rock/default_rock_coarse.pbtxt"):
            self.assertTrue(os.path.isfile(os.path.join(self.share, data)), data)
        docs = os.path.join(self.prefix, "share", "doc", "rockcut")
        for doc in ("README.md", "LICENSE", "CITATION.cff", "scene_reference.md", "outputs.md"):
            self.assertTrue(os.path.isfile(os.path.join(docs, doc)), doc)

    def test_installed_coupler_runs_an_installed_case_from_elsewhere(self):
        scene = os.path.join(self.share, "cases", "cutting", "dry_reduced.pbtxt")
        out = os.path.join(self.work, "dry")
        # PATH without the build tree: the coupler must find its modules beside itself.
        r = self.run_here([os.path.join(self.bin, "coupler"), "run", scene, "--out", out,
                           "--set", "time.end_time_s=0.004", "--no-checkpoints"],
                          path="/usr/bin:/bin")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        self.assertEqual(summary["status"], "completed")
        self.assertTrue(os.path.isfile(os.path.join(out, "run.xdmf")))

    def test_coupler_alone_finds_the_modules_on_path(self):
        # A coupler copied on its own (a user's build of it, or a wrapper directory) starts the
        # modules it finds on PATH.
        alone = os.path.join(self.root, "alone")
        os.makedirs(alone, exist_ok=True)
        shutil.copy2(os.path.join(self.bin, "coupler"), alone)
        scene = os.path.join(self.share, "cases", "cutting", "dry_reduced.pbtxt")
        out = os.path.join(self.work, "alone")
        r = self.run_here([os.path.join(alone, "coupler"), "run", scene, "--out", out,
                           "--set", "time.end_time_s=0.002", "--no-checkpoints"],
                          path=self.bin + ":/usr/bin:/bin")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # Neither beside it nor on PATH: refused, naming the module it looked for.
        r = self.run_here([os.path.join(alone, "coupler"), "run", scene, "--out", out + "2",
                           "--set", "time.end_time_s=0.002", "--no-checkpoints"],
                          path="/usr/bin:/bin")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("dem_module", r.stdout + r.stderr)

    def test_installed_scene_reference_reads_its_installed_descriptor_set(self):
        r = self.run_here([os.path.join(self.bin, "scene_reference")], path="/usr/bin:/bin")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("water_depth_m", r.stdout)
        r = self.run_here([os.path.join(self.bin, "scene_reference"), "--help"])
        self.assertIn(os.path.join(self.share, "scene_descriptor.pb"), r.stdout)


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("--build", required=True)
    p.add_argument("--tmp", required=True)
    ARGS, rest = p.parse_known_args()
    os.makedirs(ARGS.tmp, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
