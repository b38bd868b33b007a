"""Starting runs of the coupler: the one place that finds the program and sets the environment of
the runs it starts (the commands of every verb go through here).

    from rockcut import runs
    proc = runs.run("cases/cutting/dry_reduced.pbtxt", "out/x", ["time.end_time_s=0.004"])
"""
import os
import shutil
import subprocess

# The repository this package lives in when it runs from a checkout (python/rockcut/ -> the root);
# IN_CHECKOUT is False for a package installed with pip.
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
IN_CHECKOUT = (os.path.isfile(os.path.join(REPO, "CMakeLists.txt"))
               and os.path.isdir(os.path.join(REPO, "cases")))
BUILD_TREE_COUPLER = os.path.join(REPO, "build", "bin", "coupler")


def coupler(path=None):
    """The coupler to run: `path` if given, else $ROCKCUT_COUPLER, else build/bin/coupler of the
    checkout this package runs from, else `coupler` on PATH (an installation: cmake --install).
    Raises SystemExit with what to do when there is none."""
    if not path:
        path = os.environ.get("ROCKCUT_COUPLER")
    if not path and IN_CHECKOUT and os.access(BUILD_TREE_COUPLER, os.X_OK):
        path = BUILD_TREE_COUPLER
    if not path:
        path = shutil.which("coupler")
    if not path or not os.access(path, os.X_OK):
        raise SystemExit(f"rockcut: no coupler{' at ' + path if path else ''} (build it with "
                         "scripts/setup, put an installed coupler on PATH, set ROCKCUT_COUPLER, or "
                         "give --coupler PATH)")
    return path


def cases_dir():
    """The example scenes: $ROCKCUT_CASES, else cases/ of the checkout, else share/rockcut/cases
    of the installation whose coupler runs."""
    if os.environ.get("ROCKCUT_CASES"):
        return os.environ["ROCKCUT_CASES"]
    if IN_CHECKOUT:
        return os.path.join(REPO, "cases")
    prefix = os.path.dirname(os.path.dirname(os.path.realpath(coupler())))
    return os.path.join(prefix, "share", "rockcut", "cases")


def case(*parts):
    """A path under the example scenes, e.g. case("cutting", "saturated_reduced.pbtxt")."""
    return os.path.join(cases_dir(), *parts)


def default_out(name):
    """Where a verb writes by default: out/NAME of the checkout, or of the current directory for an
    installed package."""
    return os.path.join(REPO if IN_CHECKOUT else os.getcwd(), "out", name)


def cpu_count():
    """The CPUs this process may use (containers, taskset)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def dem_threads(scene, sets=(), coupler_path=None):
    """dem.threads as a run of `scene` with the overrides `sets` will see it (its effective scene;
    the default is 1)."""
    from .run_data import scalar_fields
    threads = scalar_fields(effective_scene(scene, sets, coupler_path), "dem").get("threads")
    return int(threads) if threads else 1  # dem's own field, not specimen's


def default_jobs(scene, sets=(), coupler_path=None):
    """How many runs of `scene` fit side by side: the CPUs divided by the run's DEM threads."""
    return max(1, cpu_count() // dem_threads(scene, sets, coupler_path))


def side_by_side(jobs):
    """Sets the environment for `jobs` runs at a time. Runs side by side must not poll for a reply
    before sleeping (wire/spin_wait.hpp): with more runs than cores the pollers starve each
    other; nor may their OpenMP threads spin, which the coupler lets a dry run's DEM do when it
    has the cores to itself (coupler/process/module_environment.hpp). Explicit
    ROCKCUT_WIRE_SPIN_US and OMP_WAIT_POLICY still win."""
    if jobs > 1:
        os.environ.setdefault("ROCKCUT_WIRE_SPIN_US", "0")
        if "GOMP_SPINCOUNT" not in os.environ:
            os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def command(scene, out, sets=(), coupler_path=None, transport=None):
    """The argv of `coupler run SCENE --out OUT --overwrite [--transport T] --set S ...`: the
    tool's runs replace what an earlier run of theirs left in OUT."""
    argv = [coupler(coupler_path), "run", scene, "--out", out, "--overwrite"]
    if transport:
        argv += ["--transport", transport]
    for s in sets:
        argv += ["--set", s]
    return argv


def run(scene, out, sets=(), coupler_path=None, transport=None, log=None):
    """Runs the coupler to the end; returns the CompletedProcess with its stdout and stderr. With
    `log` (a path) the command line and both streams are also written there."""
    argv = command(scene, out, sets, coupler_path, transport)
    proc = subprocess.run(argv, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    if log:
        with open(log, "w") as f:
            f.write(" ".join(argv) + "\n" + proc.stdout + proc.stderr)
    return proc


def start(argv, log):
    """Starts `argv` (command()) in the background, its output into the open file `log`, in a
    session of its own: a Ctrl-C at the terminal reaches only the caller, which then stops its runs
    itself instead of each receiving it at a random point."""
    return subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            start_new_session=True)


def effective_scene(scene, sets=(), coupler_path=None):
    """The scene as a run would use it: its bases merged and `sets` applied (`coupler validate
    SCENE --print`), as text. Raises SystemExit with the coupler's message on a bad scene."""
    argv = [coupler(coupler_path), "validate", scene, "--print"]
    for s in sets:
        argv += ["--set", s]
    proc = subprocess.run(argv, capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"rockcut: {scene}: {proc.stderr.strip()}")
    return proc.stdout.split("\n", 1)[1] if "\n" in proc.stdout else ""
