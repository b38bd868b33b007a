"""Reading a run's output folder: summary.json and run.h5 (also of a run still writing it).

    import rockcut
    run = rockcut.read_run("out/saturated_reduced")
    run.summary["force_horizontal_mean_n_per_m"]      # summary.json as a dict ({} while running)
    run.timeseries["tool_force_x_n_per_m"]             # NumPy arrays, all of one length
    run.frames.times                                   # time of each frame [s]
    run.frames[-1]["damage"]                           # one frame's fields, read when asked
    run.breaks["x_m"], run.breaks["mode"]              # one row per broken bond (None: no breaks)
    run.scene                                          # the effective scene text the run used
"""
import math
import os
import re

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")  # the run may still be writing run.h5

from .summary_file import read_summary  # noqa: E402,F401  (re-exported)

import h5py  # noqa: E402  (Debian's python3-h5py)
import numpy as np  # noqa: E402


def h5_path(path):
    """run.h5 of a run folder, or `path` itself when it names the file."""
    return os.path.join(path, "run.h5") if os.path.isdir(path) else path


def read_timeseries(f):
    """The time series of an open run.h5 as float arrays cut to one length (a partial file may be
    ragged; a series being extended by the writer is left out)."""
    if "timeseries" not in f:
        return {}
    g = f["timeseries"]
    series = {}
    for name in g.keys():
        try:
            series[name] = np.asarray(g[name][()], dtype=float)
        except (KeyError, OSError, ValueError):
            pass
    n = min((len(v) for v in series.values()), default=0)
    return {k: v[:n] for k, v in series.items()}


def read_frame(g, fields):
    """The arrays `fields` of frame group `g`, checked whole: ValueError for a frame still being
    written (empty or ragged)."""
    values = tuple(np.asarray(g[k][()]) for k in fields)
    if len(values[0]) == 0 or any(len(v) != len(values[0]) for v in values):
        raise ValueError("incomplete frame")
    return values


def stored_scene(f):
    """The scene text stored in an open run.h5 (root attribute `scene`), "" if none: the effective
    scene the run used, bases merged and --set overrides applied."""
    scene = f.attrs.get("scene", "")
    return scene.decode() if isinstance(scene, bytes) else str(scene)


def read_breaks(f):
    """/breaks of an open run.h5 as {column: array} cut to the shortest column, or None without
    them (no bond has broken, or the scene has no bonds)."""
    if "breaks" not in f:
        return None
    g = f["breaks"]
    cols = {}
    for k in g.keys():
        try:
            cols[k] = np.asarray(g[k][()])
        except (KeyError, OSError, ValueError):
            pass
    if not cols:
        return None
    n = min(len(v) for v in cols.values())
    return {k: v[:n] for k, v in cols.items()}


class Frame(dict):
    """One frame: its fields as arrays ({"position": (n, 2), "radius": (n,), ...}) and .time_s."""

    def __init__(self, time_s, fields):
        super().__init__(fields)
        self.time_s = time_s


class Frames:
    """The frames of run.h5, read one at a time when asked: len(frames), frames.times,
    frames.fields (the field names of the first frame), frames[i] (a Frame; negative i counts from
    the newest), frames.read(i, ("position", "radius")) for some fields only."""

    def __init__(self, h5):
        self.h5 = h5
        with h5py.File(h5, "r") as f:
            g = f["frames"] if "frames" in f else {}
            self.names = sorted(g.keys())
            self.times = np.array([float(g[n].attrs.get("time_s", math.nan)) for n in self.names])
            self.fields = sorted(g[self.names[0]].keys()) if self.names else []

    def __len__(self):
        return len(self.names)

    def read(self, i, fields=None):
        name = self.names[i]
        with h5py.File(self.h5, "r") as f:
            g = f["frames"][name]
            fields = list(fields or g.keys())
            return Frame(float(g.attrs.get("time_s", math.nan)), dict(zip(fields, read_frame(g, fields))))

    def __getitem__(self, i):
        return self.read(i)

    def __iter__(self):
        return (self.read(i) for i in range(len(self)))


class Run:
    """A run's output folder (see the module's doc)."""

    def __init__(self, path):
        self.path = path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
        self.h5 = h5_path(path)
        self.summary = read_summary(self.path) or {}
        if not os.path.isfile(self.h5):
            raise FileNotFoundError(f"{self.h5}: no run.h5 (give a run's --out folder)")
        with h5py.File(self.h5, "r") as f:
            self.scene = stored_scene(f)
            self.timeseries = read_timeseries(f)
            self.breaks = read_breaks(f)
        self.frames = Frames(self.h5)

    def __repr__(self):
        return (f"Run({self.path!r}: {len(self.frames)} frames, {len(self.timeseries)} time series, "
                f"{'no' if self.breaks is None else len(next(iter(self.breaks.values())))} breaks, "
                f"status {self.summary.get('status', 'running or stopped early')})")


def read_run(path):
    """The run in folder `path` (or its run.h5): see the module's doc."""
    return Run(path)


# ---------------------------------------------------------------------------------------------
# Plain-text looks into a scene (the effective text stored in run.h5, or from
# runs.effective_scene) for the few fields the verbs need without the schema.


def without_comments(text):
    """`text` with its `# ...` comments removed (the scenes hold no '#' inside strings)."""
    return re.sub(r"#[^\n]*", "", text or "")


def own_fields(text, name):
    """The body of the first `name { ... }` block of `text` (`name: { ... }` too) with its nested
    blocks blanked out, so that only the block's own fields remain (a tool's pressure_nodes hold
    fields of other messages); None without such a block. Comments must be removed first."""
    m = re.search(r"\b" + re.escape(name) + r"\s*:?\s*\{", text or "")
    if not m:
        return None
    depth, own = 1, []
    for c in text[m.end():]:
        depth += (c == "{") - (c == "}")
        if depth == 0:
            break
        own.append(c if depth == 1 and c != "}" else " ")
    return "".join(own)


def scalar_fields(text, name):
    """The numeric fields of the first `name { ... }` block of `text` as {field: float}, its nested
    blocks left out; {} without such a block. Comments are removed here."""
    own = own_fields(without_comments(text), name)
    fields = {}
    for key, value in re.findall(r"(\w+)\s*:\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\b", own or ""):
        fields[key] = float(value)
    return fields


def blocks(text, name):
    """The bodies of every `name { ... }` block of `text` in order, their nested blocks kept.
    Comments must be removed first."""
    found, pos = [], 0
    opening = re.compile(r"\b" + re.escape(name) + r"\s*:?\s*\{")
    while True:
        m = opening.search(text or "", pos)
        if not m:
            return found
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += (text[i] == "{") - (text[i] == "}")
            i += 1
        found.append(text[m.end():i - 1])
        pos = i


def vec2(body):
    """(x, y) of a Vec2 block's body; a field left out is 0 (vec2.proto's default)."""
    fields = scalar_fields("v {" + body + "}", "v")
    return fields.get("x", 0.0), fields.get("y", 0.0)


def scene_walls(scene_text):
    """The walls of a scene (dem.walls) as dicts: name, vertices (k x 2 array [m]), closed, and
    velocity_m_s (2,) [m/s]; a wall at time t lies at vertices + velocity_m_s t."""
    walls = []
    for body in blocks(without_comments(scene_text), "walls"):
        own = own_fields("w {" + body + "}", "w")  # the wall's own fields, its vertices blanked
        name = re.search(r'name\s*:\s*"([^"]*)"', own)
        velocity = blocks(body, "velocity_m_s")
        walls.append({"name": name.group(1) if name else "",
                      "vertices": np.array([vec2(v) for v in blocks(body, "vertex_m")]).reshape(-1, 2),
                      "closed": re.search(r"\bclosed\s*:\s*true", own) is not None,
                      "velocity_m_s": np.array(vec2(velocity[0]) if velocity else (0.0, 0.0))})
    return walls


def tool_block(scene_text):
    """The scalar fields of the scene's `tool { ... }` block (defaults as in scene.proto)."""
    tool = {"cutting_angle_deg": 60.0, "clearance_angle_deg": 5.0, "cutting_depth_m": 0.02,
            "width_m": 0.02, "face_length_m": 0.0, "steady_after_m": 0.0}
    tool.update(scalar_fields(scene_text, "tool"))
    if tool["face_length_m"] <= 0:
        tool["face_length_m"] = 3.0 * tool["cutting_depth_m"]
    if tool["steady_after_m"] <= 0:
        tool["steady_after_m"] = 2.0 * tool["cutting_depth_m"]
    return tool


def tool_polygon(tool, tip_x, tip_y):
    """The chisel as dem_module builds it: tip, top of the cutting face, end of the clearance face."""
    a = math.radians(tool["cutting_angle_deg"])
    b = math.radians(tool["clearance_angle_deg"])
    L = tool["face_length_m"]
    return np.array([[tip_x, tip_y],
                     [tip_x - L * math.cos(a), tip_y + L * math.sin(a)],
                     [tip_x - L * math.cos(b), tip_y + L * math.sin(b)]])
