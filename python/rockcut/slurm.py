"""Campaigns on a Slurm cluster: one job array per sweep, one array task per run.

The sweep writes the plan (DIR/tasks.tsv: one run per line) and a job-array script (DIR/job.sbatch)
a user can read, edit and submit by hand. Each task runs `coupler run CASE --out RUN --resume`: the
first start and every restart are the same command. Before its time limit the task receives USR1
(`--signal=B:USR1@MARGIN`, sent to the batch shell), stops the coupler with SIGTERM (it writes a
checkpoint and exits), and requeues itself (`scontrol requeue`): the requeued task resumes from the
checkpoint, so a run longer than the partition's time limit still completes, with the results of an
uninterrupted run.
"""
import os
import re
import shlex
import subprocess

TASKS_FILE = "tasks.tsv"
SCRIPT_FILE = "job.sbatch"
JOB_ID_FILE = "slurm_job_id"
LOG_DIR = "slurm_logs"
EXIT_CODE_FILE = "exit_code.txt"  # in a run's folder, written by its task when the run ends


def exit_code_of(run_dir):
    """The exit code a Slurm task recorded for the run in `run_dir`, or None."""
    try:
        with open(os.path.join(run_dir, EXIT_CODE_FILE)) as f:
            return int(f.read().strip())
    except (OSError, ValueError):
        return None


def parse_time_limit(text):
    """Slurm's time formats ('MM', 'MM:SS', 'HH:MM:SS', 'D-HH[:MM[:SS]]') -> seconds."""
    m = re.fullmatch(r"(?:(\d+)-)?(\d+)(?::(\d+))?(?::(\d+))?", text.strip())
    if not m:
        raise ValueError(f"not a Slurm time limit: '{text}' (e.g. 01:00:00, 90, 2-00:00:00)")
    days, a, b, c = (int(g) if g else None for g in m.groups())
    if days is not None:  # D-HH[:MM[:SS]]
        return ((days * 24 + a) * 60 + (b or 0)) * 60 + (c or 0)
    if c is not None:  # HH:MM:SS
        return (a * 60 + b) * 60 + c
    if b is not None:  # MM:SS
        return a * 60 + b
    return a * 60  # MM


def signal_margin_s(time_limit_s):
    """How long before the limit the task is warned: time for a checkpoint (a second at paper
    scale) and for Slurm's signal timing, which may come up to a minute early. Half the limit for
    short limits, at most five minutes."""
    return max(10, min(300, time_limit_s // 2))


def write_tasks(out_dir, tasks):
    """tasks: [(run_dir relative to out_dir, [coupler run arguments after --out RUN])], the
    arguments including the run's thread settings. One line per task: the run directory, a tab,
    the arguments quoted for the shell."""
    path = os.path.join(out_dir, TASKS_FILE)
    with open(path, "w") as f:
        for run_dir, args in tasks:
            f.write(run_dir + "\t" + " ".join(shlex.quote(a) for a in args) + "\n")
    return path


def job_script(out_dir, coupler, case, n_tasks, time_limit, cpus_per_task, partition=None,
               account=None, sbatch_args=(), job_name="rockcut-sweep"):
    """The job-array script: readable, editable, submittable with sbatch."""
    limit_s = parse_time_limit(time_limit)
    margin = signal_margin_s(limit_s)
    out_dir = os.path.abspath(out_dir)
    lines = [
        "#!/bin/bash",
        f"# A rockcut sweep as a Slurm job array: task i runs line i+1 of {TASKS_FILE}.",
        "# Before the time limit Slurm sends USR1 to this shell: the coupler is stopped with",
        "# SIGTERM (it writes a checkpoint), and the task requeues itself; the requeued task",
        "# resumes from the checkpoint (coupler run --resume). Submit with: sbatch " + SCRIPT_FILE,
        f"#SBATCH --job-name={job_name}",
        f"#SBATCH --array=0-{n_tasks - 1}",
        f"#SBATCH --time={time_limit}",
        f"#SBATCH --cpus-per-task={cpus_per_task}",
        f"#SBATCH --signal=B:USR1@{margin}",
        "#SBATCH --requeue",
        "#SBATCH --open-mode=append",
        f"#SBATCH --output={out_dir}/{LOG_DIR}/task_%a.log",
    ]
    if partition:
        lines.append(f"#SBATCH --partition={partition}")
    if account:
        lines.append(f"#SBATCH --account={account}")
    for arg in sbatch_args:
        lines.append(f"#SBATCH {arg}")
    lines += [
        "",
        "set -u",
        "# First of all: the warning may come at any moment, also before the run has started.",
        "pid=",
        "requeue() {",
        '  echo "time limit near: checkpoint, then requeue"',
        '  if [ -n "$pid" ]; then kill -TERM "$pid"; wait "$pid"; fi',
        '  scontrol requeue "${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}"',
        "  exit 0",
        "}",
        "trap requeue USR1",
        f"sweep={shlex.quote(out_dir)}",
        f"coupler={shlex.quote(os.path.abspath(coupler))}",
        f"case={shlex.quote(os.path.abspath(case))}",
        'line=$(sed -n "$((SLURM_ARRAY_TASK_ID + 1))p" "$sweep/' + TASKS_FILE + '")',
        'run="${line%%$\'\\t\'*}"',
        'args="${line#*$\'\\t\'}"',
        'echo "task $SLURM_ARRAY_TASK_ID (job ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}, '
        'restart ${SLURM_RESTART_COUNT:-0}) on $(hostname): $run"',
        "# A finished run is not run again (a task requeued after its run completed).",
        'if grep -qs \'"status": "completed"\' "$sweep/$run/summary.json"; then exit 0; fi',
        "# The DEM and the fluid share the task's CPUs: their idle threads sleep, and the coupler",
        "# does not poll for a reply before sleeping (tasks side by side would starve each other).",
        "export OMP_WAIT_POLICY=PASSIVE",
        'export ROCKCUT_WIRE_SPIN_US="${ROCKCUT_WIRE_SPIN_US:-0}"',
        'eval "set -- $args"',
        'mkdir -p "$sweep/$run"',
        'echo "\\$ $coupler run $case --out $sweep/$run --resume $args" >> "$sweep/$run/log.txt"',
        '"$coupler" run "$case" --out "$sweep/$run" --resume --overwrite "$@" >> "$sweep/$run/log.txt" 2>&1 &',
        "pid=$!",
        'wait "$pid"',
        "code=$?",
        "# The run's exit code, for rockcut status and collect (not written when requeued).",
        'echo "$code" > "$sweep/$run/' + EXIT_CODE_FILE + '"',
        'exit "$code"',
        "",
    ]
    return "\n".join(lines)


def write_job(out_dir, coupler, case, tasks, time_limit, cpus_per_task, partition=None,
              account=None, sbatch_args=()):
    """Writes DIR/tasks.tsv and DIR/job.sbatch; returns the script's path."""
    os.makedirs(os.path.join(out_dir, LOG_DIR), exist_ok=True)
    write_tasks(out_dir, tasks)
    script = job_script(out_dir, coupler, case, len(tasks), time_limit, cpus_per_task, partition,
                        account, sbatch_args)
    path = os.path.join(out_dir, SCRIPT_FILE)
    with open(path, "w") as f:
        f.write(script)
    os.chmod(path, 0o755)
    return path


def submit(out_dir, sbatch="sbatch"):
    """Submits DIR/job.sbatch; returns the job id (also stored in DIR/slurm_job_id)."""
    r = subprocess.run([sbatch, "--parsable", os.path.join(out_dir, SCRIPT_FILE)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("sbatch failed: " + (r.stderr.strip() or r.stdout.strip()))
    job_id = r.stdout.strip().split(";")[0]
    with open(os.path.join(out_dir, JOB_ID_FILE), "w") as f:
        f.write(job_id + "\n")
    return job_id


def job_id_of(out_dir):
    try:
        with open(os.path.join(out_dir, JOB_ID_FILE)) as f:
            return f.read().strip() or None
    except FileNotFoundError:
        return None


def task_states(job_id, squeue="squeue"):
    """{task index: 'PENDING (BeginTime)' | 'RUNNING' | ...} for the tasks Slurm still holds."""
    r = subprocess.run([squeue, "-h", "-r", "-j", str(job_id), "-o", "%K|%T|%r"],
                       capture_output=True, text=True)
    states = {}
    if r.returncode != 0:
        return states
    for line in r.stdout.splitlines():
        parts = line.strip().split("|")
        if len(parts) != 3 or not parts[0].isdigit():
            continue
        state, reason = parts[1], parts[2]
        states[int(parts[0])] = state + (f" ({reason})" if reason and reason != "None" else "")
    return states


def task_index_of_runs(out_dir):
    """{run folder relative to the sweep folder: task index} from DIR/tasks.tsv."""
    try:
        with open(os.path.join(out_dir, TASKS_FILE)) as f:
            return {line.split("\t", 1)[0]: k for k, line in enumerate(f) if line.strip()}
    except OSError:
        return {}

