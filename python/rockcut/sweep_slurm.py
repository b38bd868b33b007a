"""rockcut sweep --scheduler slurm: the runs of a sweep as one Slurm job array (slurm.py writes the
script), each task's folder prepared in the campaign directory (campaign.py). While an earlier job
of the sweep is queued, or once all its runs have completed, it collects instead of submitting.
"""
import os
import re
import sys

from . import campaign, runs, slurm
from .collect import collect_campaign
from .run_data import read_summary


def scene_blocks(scene_text):
    """The top-level blocks of a scene in text format (e.g. {'time', 'dem', 'fluid'})."""
    return set(re.findall(r"^([a-z_]+)\s*\{", scene_text, flags=re.M))


def collect_finished(out):
    """rockcut collect DIR: the CSVs and figures of what has finished, naming what is missing."""
    code = collect_campaign(out)
    return 0 if code in (0, 1) else code  # 1: nothing has finished yet, which is no error here


def submit_sweep(args, name, values, seeds):
    """Writes the job array and submits it (or, while an earlier job of this sweep is queued, says
    so). `args`: the sweep's parsed options. Returns the exit status."""
    job = slurm.job_id_of(args.out)
    if job and not args.dry_run and slurm.task_states(job):
        print(f"sweep: job {job} of {args.out} is still queued or running: not submitted again")
        return collect_finished(args.out)
    if job and not args.dry_run and all(
            (read_summary(campaign.run_dir(args.out, name, v, s)) or {}).get("status")
            == "completed" for s in (seeds or [None]) for v in values):
        print(f"sweep: every run of job {job} has completed")
        return collect_finished(args.out)
    cpus = args.cpus_per_task or runs.dem_threads(args.case, args.set, args.coupler)
    scene = runs.effective_scene(args.case, args.set, args.coupler)
    coupled = "fluid" in scene_blocks(scene)
    threads = [f"dem.threads={cpus}"] + ([f"fluid.threads={cpus}"] if coupled else [])
    campaign.write_plan(args.out, args.case, name, values, seeds, args.set, args.scheduler)
    tasks = []
    for value, seed in [(v, s) for s in (seeds or [None]) for v in values]:
        d = campaign.run_dir(args.out, name, value, seed)
        os.makedirs(d, exist_ok=True)
        sets = campaign.run_sets(args.set, name, value, seed) + threads
        argv = [a for s in sets for a in ("--set", s)]
        tasks.append((os.path.relpath(d, args.out), argv))
        cmd = runs.command(args.case, d, sets, args.coupler)
        # A folder of another command starts afresh; one of this command is resumed or, when it
        # completed, left alone by its task.
        if campaign.earlier_run(d, cmd) is None and not campaign.slurm_run_of(d, cmd):
            campaign.clear_run(d)
        campaign.write_record(d, {"command": cmd, "scheduler": "slurm"})  # no exit code yet
    script = slurm.write_job(args.out, args.coupler, args.case, tasks, args.time, cpus,
                             args.partition, args.account, args.sbatch_arg)
    print(f"sweep: {len(tasks)} runs of {args.case} as a Slurm job array: {script}")
    if args.dry_run:
        print(f"sweep: not submitted (--dry-run); submit with: sbatch {script}")
        return 0
    try:
        job = slurm.submit(args.out)
    except (RuntimeError, FileNotFoundError) as e:
        print(f"sweep: {e}", file=sys.stderr)
        return 1
    print(f"sweep: submitted job {job}; follow it with: scripts/rockcut status {args.out}\n"
          f"       and collect what has finished with: scripts/rockcut collect {args.out}")
    return 0
