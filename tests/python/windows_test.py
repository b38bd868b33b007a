#!/usr/bin/python3
"""rockcut windows run as a user would, on a 6 mm saturated reduced cut (about 5 s): its window
means against the coupler's own summary.json (computed in C++ from the same samples, so an
independent check of the selection, the signs and the node filter), windows that tile the cut,
and bad input.

  tests/python/windows_test.py --coupler build/bin/coupler --tmp DIR
"""
import csv
import json
import math
import os
import shutil
import subprocess
import unittest

import harness  # tests/python/harness.py: the command line and CSV reading

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WINDOWS = [os.path.join(ROOT, "scripts", "rockcut"), "windows"]
CASE = os.path.join(ROOT, "cases", "cutting", "saturated_reduced.pbtxt")
ARGS = None
# Both sides sum the same doubles in the same order and divide once, so they agree to the last
# bits; 1e-12 leaves room for a different order of the additions (~1e-16 per addition over a few
# hundred samples) and still fails for a wrong sign, a missed or extra sample (>= 1e-3 here).
REL = 1e-12


def read_csv(path):
    """The rows with every value but the run's name as a float."""
    with open(path) as f:
        return [{k: (v if k == "run" else float(v)) for k, v in row.items()}
                for row in csv.DictReader(f)]


def windows(*args):
    return subprocess.run([*WINDOWS, *args], capture_output=True, text=True, timeout=60)


class WindowsOfACut(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.tmp, "windows_cut")
        shutil.rmtree(cls.out, ignore_errors=True)
        run = subprocess.run(
            [ARGS.coupler, "run", CASE, "--out", cls.out, "--transport", "inproc",
             "--set", "time.end_time_s=0.007", "--set", "dem.tool.steady_after_m=0.003",
             "--set", "output.frame_interval_s=0.003", "--set", "output.timeseries_every_steps=30"],
            capture_output=True, text=True, timeout=240)
        if run.returncode != 0:
            raise RuntimeError(run.stdout + run.stderr)
        with open(os.path.join(cls.out, "summary.json")) as f:
            cls.summary = json.load(f)

    def assert_close(self, got, want, what):
        self.assertLessEqual(abs(got - want), REL * abs(want), f"{what}: {got} against {want}")

    def test_one_window_from_the_steady_start_is_the_summary(self):
        path = os.path.join(self.out, "steady.csv")
        r = windows(self.out, "--from-mm", "3", "--every-mm", "1000", "--csv", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 3.0-", r.stdout)
        rows = read_csv(path)
        self.assertEqual(len(rows), 1)
        row, s = rows[0], self.summary
        self.assertEqual(row["samples"], s["steady_samples"])
        self.assertGreater(row["samples"], 50)
        self.assert_close(row["fh_n_per_m"], s["force_horizontal_mean_n_per_m"], "Fh")
        self.assert_close(row["fv_n_per_m"], s["force_vertical_mean_n_per_m"], "Fv")
        # The largest sample and a count: the same number, not merely close.
        self.assertEqual(row["fh_peak_n_per_m"], s["force_horizontal_peak_n_per_m"])
        self.assertGreater(row["fh_peak_n_per_m"], 0.0)
        self.assert_close(row["contact_fraction"], s["tool_contact_fraction"], "contact")
        for node in ("p1", "p2", "p3"):
            if s[f"pressure_{node}_samples"] == 0:
                self.assertTrue(math.isnan(row[f"{node}_pa"]), node)
            else:
                self.assert_close(row[f"{node}_pa"], s[f"pressure_{node}_mean_pa"], node)
        for key in ("breaks_tensile", "breaks_shear", "chips"):
            self.assertEqual(row[key], s[key], key)

    def test_one_mm_windows_tile_the_cut(self):
        path = os.path.join(self.out, "mm.csv")
        r = windows(self.out, "--every-mm", "1", "--csv", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_csv(path)
        # 6 mm of cut: [0, 1), ..., [5, end]; the last sample lies a rounding past 6 mm and
        # joins the last window instead of making one of its own.
        self.assertEqual([round(w["from_m"] * 1e3, 9) for w in rows], [0, 1, 2, 3, 4, 5])
        self.assertAlmostEqual(rows[-1]["to_m"], 0.006, delta=1e-5)
        for a, b in zip(rows, rows[1:]):
            self.assertEqual(a["to_m"], b["from_m"])
            self.assertLessEqual(a["breaks_tensile"] + a["breaks_shear"],
                                 b["breaks_tensile"] + b["breaks_shear"])
        # The windows from 3 mm, weighted by their samples, make the steady mean again.
        steady = [w for w in rows if w["from_m"] >= 0.003 - 1e-12]
        samples = sum(w["samples"] for w in steady)
        self.assertEqual(samples, self.summary["steady_samples"])
        fh = sum(w["fh_n_per_m"] * w["samples"] for w in steady) / samples
        self.assertLess(abs(fh - self.summary["force_horizontal_mean_n_per_m"]),
                        1e-9 * abs(self.summary["force_horizontal_mean_n_per_m"]))

    def test_several_runs_are_tabled_and_plotted_against_depth(self):
        # The same run twice, and its run.h5 alone (as while a run is still going): three tables,
        # CSV rows whose values repeat exactly, and a plot that leaves out the run without a
        # summary.json and says so.
        going = os.path.join(self.out, "going")
        os.makedirs(going, exist_ok=True)
        shutil.copy(os.path.join(self.out, "run.h5"), going)
        path = os.path.join(self.out, "several.csv")
        png = os.path.join(self.out, "several.png")
        if os.path.exists(png):
            os.remove(png)
        r = windows(self.out, self.out, going, "--every-mm", "2", "--csv", path, "--plot", png)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.count("water depth 0 m"), 3, r.stdout)
        self.assertIn("going/run.h5: no summary.json", r.stderr)
        rows = read_csv(path)
        self.assertEqual(len(rows) % 3, 0)
        per_run = len(rows) // 3
        self.assertGreaterEqual(per_run, 3)  # 7 mm of travel in 2 mm windows
        for a, b, c in zip(rows[:per_run], rows[per_run:2 * per_run], rows[2 * per_run:]):
            for key in a:
                if key != "run":
                    self.assertEqual(repr(a[key]), repr(b[key]), key)
                    self.assertEqual(repr(a[key]), repr(c[key]), key)
            self.assertEqual(a["water_depth_m"], 0.0)
        self.assertTrue(rows[-1]["run"].endswith(os.path.join("going", "run.h5")))
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertGreater(os.path.getsize(png), 10000)
        # Nothing to plot: refused with the reason, and no PNG written.
        os.remove(png)
        r = windows(going, "--plot", png)
        self.assertEqual(r.returncode, 2)
        self.assertIn("summary.json", r.stderr)
        self.assertFalse(os.path.exists(png))

    def test_runs_at_one_depth_share_a_point_with_their_range(self):
        # A second "seed" of the cut: a copy whose stored scene says seed 2 and whose horizontal
        # force is three times the first's. The CSV names each run's seed; the plot's point at
        # the depth is the mean of the two (2x the first's Fh), its bar their range (1x to 3x).
        import h5py
        from rockcut import windows as windows_module
        seed2 = os.path.join(self.out, "seed2")
        os.makedirs(seed2, exist_ok=True)
        for name in ("run.h5", "summary.json"):
            shutil.copy(os.path.join(self.out, name), seed2)
        with h5py.File(os.path.join(seed2, "run.h5"), "r+") as f:
            scene = f.attrs["scene"]
            scene = scene.decode() if isinstance(scene, bytes) else scene
            self.assertIn("    seed: 1\n", scene)
            f.attrs["scene"] = scene.replace("    seed: 1\n", "    seed: 2\n")
            f["timeseries/tool_force_x_n_per_m"][...] *= 3.0
        path = os.path.join(self.out, "seeds.csv")
        png = os.path.join(self.out, "seeds.png")
        r = windows(self.out, seed2, "--every-mm", "2", "--csv", path, "--plot", png)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("water depth 0 m, seed 1", r.stdout)
        self.assertIn("water depth 0 m, seed 2", r.stdout)
        rows = read_csv(path)
        per_run = len(rows) // 2
        self.assertEqual([r["seed"] for r in rows], [1.0] * per_run + [2.0] * per_run)
        for a, b in zip(rows[:per_run], rows[per_run:]):
            self.assert_close(b["fh_n_per_m"], 3.0 * a["fh_n_per_m"], "Fh of the copy")
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        # The plotted points: one pressure per window start, holding both runs' values.
        runs = []
        for out in (self.out, seed2):
            h5, series = windows_module.read_series(out)
            runs.append(windows_module.Run(h5, *windows_module.run_facts(h5),
                                           windows_module.windows(series, 0.002, 0.0)))
        fh = lambda w: w["fh_n_per_m"]  # noqa: E731
        points = windows_module.depth_points(runs, 0.002, fh)
        full = [w for w in rows[:per_run] if w["to_m"] - w["from_m"] >= 0.99 * 0.002]
        self.assertEqual(len(points), len(full))  # the short last window is not drawn
        for w, (start, at) in zip(full, points.items()):
            self.assertAlmostEqual(start, w["from_m"], delta=1e-12)
            self.assertEqual(len(at), 1)
            p_hydro, values = at[0]
            self.assertEqual(p_hydro, self.summary["hydrostatic_pressure_pa"])
            self.assertEqual(len(values), 2)
            self.assertAlmostEqual(sum(values) / 2, 2.0 * w["fh_n_per_m"],
                                   delta=REL * 2.0 * abs(w["fh_n_per_m"]))

    def test_runs_are_drawn_against_travel(self):
        # A copy whose stored scene says 2000 m and whose vertical force is doubled stands for a
        # second depth. Each run is one line per panel, labelled with its depth; every window is
        # a step over its own travel with the CSV's value.
        import h5py
        from rockcut import windows as windows_module
        deep = os.path.join(self.out, "deep")
        os.makedirs(deep, exist_ok=True)
        shutil.copy(os.path.join(self.out, "run.h5"), deep)
        with h5py.File(os.path.join(deep, "run.h5"), "r+") as f:
            scene = f.attrs["scene"]
            scene = scene.decode() if isinstance(scene, bytes) else scene
            f.attrs["scene"] = "water_depth_m: 2000\n" + scene
            f["timeseries/tool_force_y_n_per_m"][...] *= 2.0
        path = os.path.join(self.out, "travel.csv")
        png = os.path.join(self.out, "travel.png")
        if os.path.exists(png):
            os.remove(png)
        r = windows(self.out, deep, "--every-mm", "1", "--csv", path, "--plot-travel", png)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(f"plot: {png}", r.stdout)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertGreater(os.path.getsize(png), 10000)
        rows = read_csv(path)
        per_run = len(rows) // 2
        runs = []
        for out in (self.out, deep):
            h5, series = windows_module.read_series(out)
            runs.append(windows_module.Run(h5, *windows_module.run_facts(h5),
                                           windows_module.windows(series, 0.001, 0.0)))
        panels = windows_module.window_panels(coupled=True)
        lines = windows_module.travel_lines(runs, panels)
        self.assertEqual(len(lines), 8)  # Fh, Fv, shear fraction, chip area, P1-P3, cavitated
        fv = lines["Fv, up > 0 [kN/m]"]
        self.assertEqual([name for name, _, _ in fv], ["windows_cut: 0 m", "deep: 2000 m"])
        for (name, xs, ys), mine, factor in ((fv[0], rows[:per_run], 1.0),
                                             (fv[1], rows[:per_run], 2.0)):
            self.assertEqual(len(xs), 2 * per_run, name)
            for k, w in enumerate(mine):
                self.assertAlmostEqual(xs[2 * k], w["from_m"] * 1e3, delta=1e-9)
                self.assertAlmostEqual(xs[2 * k + 1], w["to_m"] * 1e3, delta=1e-9)
                want = factor * w["fv_n_per_m"] * 1e-3
                self.assertEqual(ys[2 * k], ys[2 * k + 1])
                self.assertLessEqual(abs(ys[2 * k] - want), REL * abs(want), name)
        # Nowhere to write it: refused before anything is read.
        r = windows(self.out, "--plot-travel", os.path.join(self.out, "no_such", "t.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("--plot-travel", r.stderr)

    def test_the_breaks_are_placed_against_the_tool_tip(self):
        # The run's own breaks: every bond broken in the cut falls in exactly one window, so the
        # window counts add up to the time series' tensile + shear count at its end.
        path = os.path.join(self.out, "placed.csv")
        r = windows(self.out, "--every-mm", "1", "--csv", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("ahead [mm]", r.stdout)
        rows = read_csv(path)
        last = rows[-1]
        self.assertGreater(last["breaks_tensile"] + last["breaks_shear"], 0)
        self.assertEqual(sum(w["window_breaks"] for w in rows),
                         last["breaks_tensile"] + last["breaks_shear"])
        # A run still going: the coupler has written the breaks up to its newest frame only. A
        # copy without its two newest frames leaves the breaks' columns of the windows after the
        # frame then newest unknown ('-', NaN in the CSV), and those before it as they were.
        import h5py
        import numpy as np
        going = os.path.join(self.out, "breaks_going")
        os.makedirs(going, exist_ok=True)
        shutil.copy(os.path.join(self.out, "run.h5"), going)
        with h5py.File(os.path.join(going, "run.h5"), "r+") as f:
            names = sorted(f["frames"].keys())
            self.assertGreaterEqual(len(names), 3)
            for name in names[-2:]:
                del f["frames"][name]
            covered = float(f["frames"][names[-3]].attrs["time_s"])
            covered_travel = float(np.interp(covered, f["timeseries/time_s"][()],
                                             f["timeseries/tool_travel_m"][()]))
            travel = f["timeseries/tool_travel_m"][()]
        self.assertGreater(covered, 0.0)
        path = os.path.join(self.out, "breaks_going.csv")
        r = windows(going, "--every-mm", "1", "--csv", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        cut = read_csv(path)
        self.assertEqual(len(cut), len(rows))
        unknown = 0
        for w, whole in zip(cut, rows):
            # Known exactly when the window's last sample is no later than the newest frame (the
            # tool moves at a constant velocity, so later in time is further in travel).
            last = travel[(travel >= w["from_m"]) & (travel <= w["to_m"])].max()
            self.assertEqual(math.isnan(w["window_breaks"]), last > covered_travel,
                             (w["from_m"], w["to_m"], covered_travel))
            if math.isnan(w["window_breaks"]):
                unknown += 1
                self.assertTrue(math.isnan(w["break_ahead_median_m"]))
            else:
                self.assertEqual(unknown, 0, "a known window after an unknown one")
                self.assertEqual(w["window_breaks"], whole["window_breaks"])
                self.assertEqual(repr(w["break_ahead_median_m"]),
                                 repr(whole["break_ahead_median_m"]))
        self.assertGreater(unknown, 0)
        self.assertLess(unknown, len(cut))

        # A copy whose breaks are replaced by three per time-series sample, at the tip's place
        # at that sample plus (3 mm ahead, 1 mm below), (5 mm ahead, 2 mm below) and (7 mm
        # ahead, 1 mm above): every window holds three times its samples, their median lies
        # 5 mm ahead, and two thirds of them below the tip. A sign error in the cutting direction
        # or the height (a third below), or breaks put in the wrong window by their time, moves
        # these by whole millimetres, thirds or samples.
        placed = os.path.join(self.out, "placed")
        os.makedirs(placed, exist_ok=True)
        shutil.copy(os.path.join(self.out, "run.h5"), placed)
        with h5py.File(os.path.join(placed, "run.h5"), "r+") as f:
            ts = f["timeseries"]
            t = np.asarray(ts["time_s"][()], dtype=float)
            tip_x = np.asarray(ts["tool_tip_x_m"][()], dtype=float)
            tip_y = np.asarray(ts["tool_tip_y_m"][()], dtype=float)
            self.assertGreater(tip_x[-1], tip_x[0])  # the scene cuts towards +x
            n = 3 * len(t)
            new = {"time_s": np.repeat(t, 3),
                   "x_m": np.ravel(np.column_stack([tip_x + 0.003, tip_x + 0.005,
                                                    tip_x + 0.007])),
                   "y_m": np.ravel(np.column_stack([tip_y - 0.001, tip_y - 0.002,
                                                    tip_y + 0.001])),
                   "mode": np.zeros(n), "step": np.zeros(n, dtype=np.uint64)}
            for name, values in new.items():
                if name in f["breaks"]:
                    del f["breaks"][name]
                f["breaks"].create_dataset(name, data=values)
        path = os.path.join(self.out, "placed_copy.csv")
        r = windows(placed, "--every-mm", "2", "--csv", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_csv(path)
        self.assertGreaterEqual(len(rows), 3)
        for w in rows:
            self.assertEqual(w["window_breaks"], 3 * w["samples"], w["from_m"])
            self.assertAlmostEqual(w["break_ahead_median_m"], 0.005, delta=1e-9)
            self.assertAlmostEqual(w["break_below_tip_fraction"], 2 / 3, delta=1e-12)

    def test_what_lies_on_the_tool_is_counted_per_frame(self):
        # The run's last frame in a copy, with every disc moved far below the tip and made loose but four
        # groups placed around the tool tip of that frame's time (the block's top surface is
        # read from the first frame, which stays as written):
        #   A: 5 discs 20 mm behind the tip, 1 mm above the surface, bonded     -> above, at tool
        #   B: 3 discs 5 mm ahead of the tip, 1 mm above the surface, loose     -> above, at tool, loose
        #   C: 2 discs 60 mm behind the tip, 1 mm above the surface, loose      -> above only
        #   D: 4 discs 5 mm ahead of the tip, 1 mm above the tip, loose         -> loose only
        # A sign error in the cutting direction swaps which of A, B and C count; a wrong window
        # edge, surface height or damage threshold, or loose discs counted below the tip, moves
        # the counts by whole groups.
        import h5py
        import numpy as np
        from rockcut import windows as windows_module
        r = windows(self.out, "--frames")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("loose at the tool", r.stdout)
        pile = os.path.join(self.out, "pile")
        os.makedirs(pile, exist_ok=True)
        shutil.copy(os.path.join(self.out, "run.h5"), pile)
        h5 = os.path.join(pile, "run.h5")
        _, series = windows_module.read_series(h5)
        with h5py.File(h5, "r+") as f:
            names = sorted(f["frames"].keys())
            self.assertGreaterEqual(len(names), 3)
            first = f["frames"][names[0]]
            top = float((first["position"][()][:, 1] + first["radius"][()]).max())
            g = f["frames"][names[-1]]
            time = float(g.attrs["time_s"])
            tx = float(np.interp(time, series["time_s"], series["tool_tip_x_m"]))
            ty = float(np.interp(time, series["time_s"], series["tool_tip_y_m"]))
            pos = np.array(g["position"][()])
            damage = np.ones(len(pos))
            pos[:, 0], pos[:, 1] = tx, -1.0
            groups = [(5, -0.020, top + 0.001, 0.0), (3, 0.005, top + 0.001, 1.0),
                      (2, -0.060, top + 0.001, 1.0), (4, 0.005, ty + 0.001, 1.0)]
            k = 0
            for count, ahead, y, d in groups:
                pos[k:k + count, 0] = tx + ahead
                pos[k:k + count, 1] = y
                damage[k:k + count] = d
                k += count
            g["position"][...] = pos
            g["damage"][...] = damage
            radius = np.array(g["radius"][()])
        rows = windows_module.pile_rows(h5, series)
        last = rows[-1]
        self.assertEqual(last["time_s"], time)
        self.assertEqual(last["above_surface"], 10)
        self.assertEqual(last["at_tool"], 8)
        self.assertEqual(last["loose_at_tool"], 7)
        area = float(np.pi * (radius[:8] ** 2).sum())
        self.assertLessEqual(abs(last["at_tool_area_m2"] - area), 1e-12 * area)
        # Frames without the damage field: refused, naming the field to add.
        with h5py.File(h5, "r+") as f:
            for name in f["frames"]:
                del f["frames"][name]["damage"]
        r = windows(pile, "--frames")
        self.assertEqual(r.returncode, 2)
        self.assertIn("damage", r.stderr)
        self.assertIn("output.frame_fields", r.stderr)

    def test_the_steady_force_is_fitted_from_the_steady_start(self):
        # A copy whose horizontal force is 500 kN/m flat before the steady start (3 mm here) and
        # 100 kN/m + 20 kN/m per mm of travel from it on: the fit must give 20.00 exactly and the
        # mean of the line's samples. A fit that took the flat part in, or started anywhere but
        # at 3 mm, gives another slope (it falls to about 13 with the first 3 mm included).
        # Printed to 0.01 kN/m per mm: the least squares of an exact line are exact to ~1e-12.
        import h5py
        import numpy as np
        line = os.path.join(self.out, "line")
        os.makedirs(line, exist_ok=True)
        for name in ("run.h5", "summary.json"):
            shutil.copy(os.path.join(self.out, name), line)
        with h5py.File(os.path.join(line, "run.h5"), "r+") as f:
            travel = f["timeseries/tool_travel_m"][...]
            steady = travel >= 0.003
            fh = np.where(steady, 1e5 + 2e7 * travel, 5e5)
            f["timeseries/tool_force_x_n_per_m"][...] = -fh
        want = (f"steady part from 3.0 mm: {int(steady.sum())} samples, "
                f"Fh mean {fh[steady].mean() * 1e-3:.1f} kN/m, slope 20.00 kN/m per mm")
        r = windows(line)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(want, r.stdout)
        # Without summary.json (a run still going) the start comes from the stored scene, which
        # holds the run's --set dem.tool.steady_after_m=0.003; without that field, from its
        # default of two cutting depths (40 mm), which this 6 mm cut has not reached.
        os.remove(os.path.join(line, "summary.json"))
        r = windows(line)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(want, r.stdout)
        with h5py.File(os.path.join(line, "run.h5"), "r+") as f:
            scene = f.attrs["scene"]
            scene = scene.decode() if isinstance(scene, bytes) else scene
            self.assertIn("steady_after_m", scene)
            f.attrs["scene"] = "\n".join(s for s in scene.split("\n") if "steady_after_m" not in s)
        r = windows(line)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("steady part from 40.0 mm: not reached", r.stdout)

    def test_bad_input_is_refused_with_the_reason(self):
        missing = os.path.join(self.out, "no_such_run")
        r = windows(missing)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no_such_run", r.stderr)
        r = windows(self.out, "--every-mm", "0")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--every-mm", r.stderr)
        r = windows(self.out, "--from-mm", "50")
        self.assertEqual(r.returncode, 2)
        self.assertIn("reached", r.stderr)
        r = windows(self.out, "--plot", os.path.join(missing, "depth.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("--plot", r.stderr)
        # A plot with nothing to draw (the one window, 3-6 mm, is shorter than --every-mm) is
        # refused before the CSV is written, rather than drawn empty.
        png, path = os.path.join(self.out, "empty.png"), os.path.join(self.out, "empty.csv")
        r = windows(self.out, "--from-mm", "3", "--every-mm", "1000", "--plot", png, "--csv", path)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no window of full width", r.stderr)
        self.assertIn("smaller --every-mm", r.stderr)
        self.assertFalse(os.path.exists(png))
        self.assertFalse(os.path.exists(path))
        r = windows(self.out, "--from-mm", "3", "--every-mm", "3", "--plot", png)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.exists(png))
        self.assertFalse(os.path.exists(missing))


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
