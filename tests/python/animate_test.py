#!/usr/bin/python3
"""rockcut animate on a short run of the default scene (saturated_reduced, 5 ms, 6 frames, about
4 s): an MP4 that ffprobe reads as H.264 with one picture per frame and the duration the frame
rate gives, a GIF, and clear refusals.

  tests/python/animate_test.py --coupler build/bin/coupler --tmp DIR
"""
import json
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line
from rockcut import runs

ROCKCUT = os.path.join(runs.REPO, "scripts", "rockcut")
ARGS = None
FRAMES = 6  # t = 0, 1, ..., 5 ms
FPS = 4


def probe(path):
    """ffprobe's view of the first video stream (counting the frames by decoding them)."""
    r = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames",
                        "-show_entries", "stream=codec_name,nb_read_frames,width,height,pix_fmt",
                        "-show_entries", "format=duration,format_name", "-of", "json", path],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    info = json.loads(r.stdout)
    return info["streams"][0], info["format"]


class Animate(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "animate")
        shutil.rmtree(cls.out, ignore_errors=True)
        proc = runs.run(runs.case("cutting", "saturated_reduced.pbtxt"), cls.out,
                        ["time.end_time_s=0.005", "output.frame_interval_s=0.001"], ARGS.coupler)
        assert proc.returncode == 0, proc.stderr

    def animate(self, *args):
        return subprocess.run([ROCKCUT, "animate", self.out, *args], capture_output=True,
                              text=True, timeout=120)

    def test_mp4_is_h264_with_one_picture_per_frame(self):
        mp4 = os.path.join(self.out, "pressure.mp4")
        r = self.animate("--color", "pressure", "-o", mp4, "--fps", str(FPS), "--width-px", "480")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn(f"({FRAMES} frames)", r.stdout)
        stream, fmt = probe(mp4)
        self.assertEqual(stream["codec_name"], "h264")
        self.assertEqual(stream["pix_fmt"], "yuv420p")  # what players expect
        self.assertEqual(int(stream["nb_read_frames"]), FRAMES)
        self.assertEqual(int(stream["width"]), 480)
        self.assertIn("mp4", fmt["format_name"])
        self.assertAlmostEqual(float(fmt["duration"]), FRAMES / FPS, delta=0.5 / FPS)

    def test_default_is_damage_into_cut_mp4(self):
        r = self.animate("--width-px", "320")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        stream, _ = probe(os.path.join(self.out, "cut.mp4"))
        self.assertEqual(int(stream["nb_read_frames"]), FRAMES)

    def test_gif(self):
        r = self.animate("--gif", "--color", "velocity", "--width-px", "320")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        with open(os.path.join(self.out, "cut.gif"), "rb") as f:
            self.assertEqual(f.read(6), b"GIF89a")
        stream, _ = probe(os.path.join(self.out, "cut.gif"))
        self.assertEqual(int(stream["nb_read_frames"]), FRAMES)

    def test_refusals_name_what_is_missing(self):
        r = subprocess.run([ROCKCUT, "animate", os.path.join(ARGS.tmp, "nowhere")],
                           capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no run.h5", r.stderr)
        r = self.animate("--color", "temperature")
        self.assertEqual(r.returncode, 2)
        self.assertIn("invalid choice", r.stderr)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
