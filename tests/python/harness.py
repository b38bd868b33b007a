"""What the tests of the rockcut package (tests/python/*_test.py) share: their command line, as
ctest gives it (--coupler PATH --tmp DIR, tests/CMakeLists.txt), and reading a CSV the verbs wrote.

  if __name__ == "__main__":
      ARGS, rest = harness.arguments()
      harness.run(rest)
"""
import argparse
import csv
import os
import sys
import unittest


def arguments():
    """(args with .coupler and .tmp, the rest of the command line for unittest); makes .tmp."""
    p = argparse.ArgumentParser()
    p.add_argument("--coupler", required=True)
    p.add_argument("--tmp", required=True)
    args, rest = p.parse_known_args()
    os.makedirs(args.tmp, exist_ok=True)
    return args, rest


def run(rest):
    """The tests of the script being run (__main__), verbosely."""
    unittest.main(module="__main__", argv=[sys.argv[0]] + rest, verbosity=2)


def read_csv(path):
    """The rows of a CSV file as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))
