#!/usr/bin/python3
"""Every script a user or the docs start by its path runs as written: each file with a `#!` line
in scripts/, bench/ and .ci/ is executable, and its interpreter is Debian's (the `python3` first
on PATH may be another one that does not see Debian's numpy and h5py).

  tests/structure/entry_points_test.py SOURCE_DIR
"""
import os
import sys
import unittest

FOLDERS = ("scripts", "bench", ".ci")
ALLOWED_INTERPRETERS = ("#!/usr/bin/env bash", "#!/bin/bash", "#!/bin/sh", "#!/usr/bin/python3")


def scripts(root):
    """(path relative to root, first line) of every file in FOLDERS that starts with #!."""
    found = []
    for folder in FOLDERS:
        top = os.path.join(root, folder)
        if not os.path.isdir(top):
            continue
        for name in sorted(os.listdir(top)):
            path = os.path.join(top, name)
            if not os.path.isfile(path):
                continue
            with open(path, "rb") as f:
                first = f.readline().decode("utf-8", "replace").rstrip("\n")
            if first.startswith("#!"):
                found.append((os.path.join(folder, name), first))
    return found


class EntryPoints(unittest.TestCase):
    def test_every_script_is_executable_with_a_debian_interpreter(self):
        found = scripts(ROOT)
        # The entry points the README and the docs name must be among them.
        names = {path for path, _ in found}
        for named in ("scripts/run", "scripts/test", "scripts/rockcut", "bench/bench_whole_cut.py",
                      "bench/bench_real_cut.py", "bench/scaling_model.py", ".ci/run"):
            self.assertIn(named, names)
        for path, first in found:
            with self.subTest(script=path):
                self.assertTrue(os.access(os.path.join(ROOT, path), os.X_OK),
                                "%s starts with %r but is not executable (chmod +x, and git add)"
                                % (path, first))
                self.assertIn(first, ALLOWED_INTERPRETERS,
                              "%s: interpreter %r; allowed: %s" % (path, first, ALLOWED_INTERPRETERS))


if __name__ == "__main__":
    ROOT = os.path.abspath(sys.argv.pop(1))
    unittest.main()
