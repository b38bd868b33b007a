#!/usr/bin/python3
"""The rockcut package as a user installs it: `pip install --no-build-isolation --no-deps` of python/
into a fresh virtual environment that sees Debian's numpy, h5py and matplotlib (no network:
--no-index; --no-deps because Debian's h5py registers as "h5py._debian_h5py_serial", which pip
cannot match to the declared "h5py", though `import h5py` works),
then its `rockcut` command and `import rockcut` from outside the checkout, with neither PYTHONPATH
nor the checkout's build tree to lean on. About 10 s.

  tests/python/package_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import sys
import unittest

import harness  # tests/python/harness.py: the command line
from rockcut import runs

ARGS = None


def clean_env(**extra):
    """The environment of a user's shell: no PYTHONPATH pointing into the checkout, no
    ROCKCUT_COUPLER; `extra` on top."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ROCKCUT_COUPLER")}
    env.update(extra)
    return env


class InstalledPackage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.root = os.path.join(ARGS.tmp, "package")
        shutil.rmtree(cls.root, ignore_errors=True)
        os.makedirs(cls.root)
        # A copy of python/: setuptools builds in the source folder (build/, *.egg-info), which
        # must not land in the checkout or race another test reading it.
        cls.src = os.path.join(cls.root, "src")
        shutil.copytree(os.path.join(runs.REPO, "python"), cls.src,
                        ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
        cls.venv = os.path.join(cls.root, "venv")
        subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", cls.venv],
                       check=True, capture_output=True, timeout=120)
        cls.bin = os.path.join(cls.venv, "bin")
        cls.install = subprocess.run(
            [os.path.join(cls.bin, "pip"), "install", "--no-build-isolation", "--no-index",
             "--no-deps", "--disable-pip-version-check", cls.src],
            capture_output=True, text=True, timeout=300, env=clean_env(), cwd=cls.root)
        # A directory outside the checkout, as a user's working directory.
        cls.work = os.path.join(cls.root, "work")
        os.makedirs(cls.work)

    def run_in_venv(self, argv, **env):
        return subprocess.run(argv, capture_output=True, text=True, timeout=120, cwd=self.work,
                              env=clean_env(**env))

    def test_pip_install_succeeds_offline_with_declared_dependencies(self):
        self.assertEqual(self.install.returncode, 0, self.install.stdout + self.install.stderr)
        r = self.run_in_venv([os.path.join(self.bin, "pip"), "show", "rockcut"])
        self.assertEqual(r.returncode, 0, r.stderr)
        requires = [line for line in r.stdout.splitlines() if line.startswith("Requires:")]
        self.assertEqual(requires, ["Requires: h5py, matplotlib, numpy"])

    def test_rockcut_help_from_the_console_script(self):
        r = self.run_in_venv([os.path.join(self.bin, "rockcut"), "--help"])
        self.assertEqual(r.returncode, 0, r.stderr)
        for verb in ("sweep", "plot", "calibrate", "regression"):
            self.assertIn(f"  {verb}", r.stdout)
        # The installed copy, not the checkout's python/.
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c",
                              "import rockcut; print(rockcut.__file__)"])
        self.assertTrue(r.stdout.strip().startswith(self.venv), r.stdout + r.stderr)

    def test_help_needs_neither_h5py_nor_numpy_nor_matplotlib(self):
        # None in sys.modules makes `import h5py` raise ImportError, as where it is not installed.
        code = ("import sys\n"
                "for m in ('h5py', 'numpy', 'matplotlib'): sys.modules[m] = None\n"
                "from rockcut.__main__ import main\n"
                "sys.exit(main(['--help']))\n")
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c", code])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("usage: rockcut VERB", r.stdout)

    def test_status_needs_neither_h5py_nor_numpy_nor_matplotlib(self):
        # `rockcut status` on a cluster's login node: a sweep folder of one finished and one
        # pending run, read with the standard library only.
        sweep = os.path.join(self.work, "sweep")
        done = os.path.join(sweep, "water_depth_m=0", "seed=1")
        os.makedirs(done, exist_ok=True)
        os.makedirs(os.path.join(sweep, "water_depth_m=10", "seed=1"), exist_ok=True)
        with open(os.path.join(sweep, "sweep_plan.json"), "w") as f:
            json.dump({"case": "cases/cutting/dry_reduced.pbtxt", "name": "water_depth_m",
                       "values": ["0", "10"], "seeds": [1], "set": [], "scheduler": "local"}, f)
        with open(os.path.join(done, "summary.json"), "w") as f:
            json.dump({"status": "completed", "wall_time_s": 1.5}, f)
        code = ("import sys\n"
                "for m in ('h5py', 'numpy', 'matplotlib'): sys.modules[m] = None\n"
                "from rockcut.__main__ import main\n"
                "sys.exit(main(['status', sys.argv[1]]))\n")
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c", code, sweep])
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("1 done", r.stdout)

    def test_finds_the_coupler_on_path_and_reads_a_run(self):
        coupler_dir = os.path.dirname(os.path.abspath(ARGS.coupler))
        path = coupler_dir + os.pathsep + os.environ.get("PATH", "")
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c",
                              "from rockcut import runs; print(runs.coupler())"], PATH=path)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(os.path.realpath(r.stdout.strip()), os.path.realpath(ARGS.coupler))
        # Without it on PATH the installed package says what to do, not a traceback.
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c",
                              "from rockcut import runs; runs.coupler()"], PATH="/usr/bin:/bin")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("no coupler", r.stderr)
        self.assertNotIn("Traceback", r.stderr)

        out = os.path.join(self.work, "dry")
        scene = os.path.join(runs.REPO, "cases", "cutting", "dry_reduced.pbtxt")
        proc = subprocess.run([ARGS.coupler, "run", scene, "--out", out, "--overwrite",
                               "--set", "time.end_time_s=0.004", "--no-checkpoints"],
                              capture_output=True, text=True, timeout=120)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        code = ("import json, sys, rockcut\n"
                "run = rockcut.read_run(sys.argv[1])\n"
                "print(json.dumps({'status': run.summary['status'],\n"
                "                  'rows': len(run.timeseries['time_s']),\n"
                "                  'frames': len(run.frames.times)}))\n")
        r = self.run_in_venv([os.path.join(self.bin, "python"), "-c", code, out])
        self.assertEqual(r.returncode, 0, r.stderr)
        seen = json.loads(r.stdout)
        self.assertEqual(seen["status"], "completed")
        self.assertGreater(seen["rows"], 1)
        self.assertGreaterEqual(seen["frames"], 1)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
