#!/usr/bin/python3
"""A run whose output cannot grow (a file-size limit, a full disk) stops with exit 5 and one error
line, and leaves run.h5 readable with every frame it had written, at any moment the room runs out.

Ten file-size limits (`ulimit -f`, RLIMIT_FSIZE set in the child) spread from the first frame to
the last of a short dry cut, and, where the test runs as root, ten tmpfs file systems of as many
sizes mounted as --out. After each: exit 5, "error: writing the output failed" on stderr once,
run.h5 opens, every frame group in it reads whole, run.xdmf lists exactly those frames, and the
time series reads. About 40 s.

  tests/python/full_disk_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
import resource
import shutil
import subprocess
import unittest
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import harness  # tests/python/harness.py: the command line
from rockcut import runs

ARGS = None
SCENE = runs.case("cutting", "dry_reduced.pbtxt")
# 21 frames of 647 discs with four fields (about 30 kB each before compression) over 10 ms.
SETS = ["time.end_time_s=0.01", "output.frame_interval_s=0.0005", "output.timeseries_every_steps=20"]
# From below what the first rows need (a chunk of every time-series column, about 0.45 MB) to near
# the run's whole run.h5 (1.7 MB).
LIMITS_KIB = [200, 450, 600, 750, 900, 1050, 1200, 1350, 1500, 1600]


def check_readable(test, out, proc, label):
    stderr = proc.stderr
    test.assertEqual(proc.returncode, 5, f"{label}: {proc.stdout}{stderr}")
    test.assertEqual(stderr.count("error: writing the output failed"), 1, f"{label}: {stderr}")
    with h5py.File(os.path.join(out, "run.h5"), "r") as f:
        frames = sorted(f["frames"].keys())
        for name in frames:
            group = f["frames"][name]
            n = group["position"].shape[0]
            for field in group:
                values = group[field][()]
                test.assertEqual(values.shape[0], n, f"{label}: frame {name}/{field}")
                test.assertTrue(np.all(np.isfinite(values)), f"{label}: frame {name}/{field}")
        time_s = f["timeseries"]["time_s"][()]
        test.assertTrue(np.all(np.diff(time_s) > 0), f"{label}: time series out of order")
        status = f.attrs.get("status", "")
        test.assertIn("failed", status if isinstance(status, str) else status.decode(), label)
    # The XDMF index names exactly the frames in the file.
    root = ET.parse(os.path.join(out, "run.xdmf")).getroot()
    indexed = sorted({item.text.strip().split(":")[1].split("/")[2]
                      for item in root.iter("DataItem") if item.text and "/frames/" in item.text})
    test.assertEqual(indexed, frames, label)
    return len(frames)


class FullDisk(unittest.TestCase):
    def run_limited(self, out, limit_bytes=None):
        def limit():
            if limit_bytes is not None:
                resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
        argv = runs.command(SCENE, out, SETS, ARGS.coupler)
        return subprocess.run(argv, capture_output=True, text=True, timeout=120,
                              preexec_fn=limit, stdin=subprocess.DEVNULL)

    def test_file_size_limit_at_ten_moments(self):
        frames_kept = []
        for kib in LIMITS_KIB:
            out = os.path.join(ARGS.tmp, "full_disk", f"limit_{kib}k")
            shutil.rmtree(out, ignore_errors=True)
            proc = self.run_limited(out, kib * 1024)
            frames_kept.append(check_readable(self, out, proc, f"ulimit -f {kib} KiB"))
        print("frames kept per limit:", frames_kept)
        # The limits reach from before the first frames to near the end: the runs stopped at
        # different moments, and the later the limit, the more frames stayed.
        self.assertEqual(frames_kept, sorted(frames_kept))
        self.assertEqual(frames_kept[0], 0)
        self.assertGreater(frames_kept[-1], 10)

    @unittest.skipUnless(os.geteuid() == 0 and shutil.which("mount"), "tmpfs needs root")
    def test_full_tmpfs_at_ten_moments(self):
        frames_kept = []
        for kib in LIMITS_KIB:
            mount_point = os.path.join(ARGS.tmp, "full_disk", f"tmpfs_{kib}k")
            os.makedirs(mount_point, exist_ok=True)
            r = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={kib}k", "tmpfs", mount_point],
                               capture_output=True, text=True)
            if r.returncode != 0:
                self.skipTest(f"cannot mount a tmpfs: {r.stderr.strip()}")
            try:
                out = os.path.join(mount_point, "run")
                proc = self.run_limited(out)
                frames_kept.append(check_readable(self, out, proc, f"tmpfs of {kib} KiB"))
            finally:
                subprocess.run(["umount", mount_point], capture_output=True)
        print("frames kept per size:", frames_kept)
        self.assertEqual(frames_kept, sorted(frames_kept))
        self.assertGreater(frames_kept[-1], 5)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
