#!/usr/bin/python3
"""A clone stands alone: no file of the project reads or cites the folder beside the checkout that
a developer's machine may have (a user's clone has none). Walks the source tree (build
directories, output and .git left out) for the relative path to it.

  tests/install/self_contained_test.py SOURCE_DIR
"""
import os
import sys

# Written in two parts so that this file does not find itself.
NEEDLE = ".." + "/shared"
SKIP_DIRS = {".git", "out", "__pycache__"}


def offending_lines(root):
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in files:
            path = os.path.join(folder, name)
            try:
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        if NEEDLE in line:
                            found.append(f"{os.path.relpath(path, root)}:{number}: {line.strip()}")
            except (UnicodeDecodeError, OSError):
                continue  # binary files (films, HDF5) cannot cite a path
    return found


if __name__ == "__main__":
    lines = offending_lines(sys.argv[1])
    if lines:
        print("files that read or cite " + NEEDLE + " (move what they need into the project):")
        print("\n".join(lines))
        sys.exit(1)
    print("no file reads or cites " + NEEDLE)
