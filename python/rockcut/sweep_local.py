"""rockcut sweep on this machine: the runs of a sweep, --jobs at a time, each into its folder of the
campaign directory (campaign.py), skipping the runs that completed earlier and continuing the
interrupted ones from their checkpoints.
"""
import os
import signal
import subprocess
import sys
import time

from . import campaign, runs
from .run_data import read_summary


def start_run(args, name, value, seed):
    d = campaign.run_dir(args.out, name, value, seed)
    os.makedirs(d, exist_ok=True)
    cmd = runs.command(args.case, d, campaign.run_sets(args.set, name, value, seed), args.coupler)
    resume = campaign.earlier_run(d, cmd) == "resume"
    if not resume:
        campaign.clear_run(d)
    log = open(os.path.join(d, campaign.LOG), "a" if resume else "w")
    log.write("$ " + " ".join(cmd + (["--resume"] if resume else [])) + "\n")
    log.flush()
    proc = runs.start(cmd + (["--resume"] if resume else []), log)
    # Started, not finished: `rockcut status` tells a run still going from one whose sweep stopped.
    campaign.write_record(d, {"command": cmd, "pid": proc.pid})
    return proc, log, time.monotonic(), cmd


def finish_run(args, name, value, seed, proc, log, t0, cmd):
    """Records the run's exit code beside its output (for --plot-only) and prints its line."""
    log.close()
    wall = time.monotonic() - t0
    d = campaign.run_dir(args.out, name, value, seed)
    campaign.write_record(d, {"command": cmd, "exit_code": proc.returncode, "sweep_wall_s": wall})
    summary = read_summary(d)
    status = summary.get("status") if summary else "no summary.json"
    ok = proc.returncode == 0
    label = campaign.run_label(name, value, seed)
    print(f"{label}: {'ok' if ok else 'FAILED'}, status {status}, {wall:.1f} s wall, "
          f"exit code {proc.returncode}" + ("" if ok else f"  (see {d}/log.txt)"), flush=True)
    return ok


def run_sweep(args, name, values, seeds):
    """Runs every value (and seed), --jobs at a time. `args`: the sweep's parsed options (case,
    out, set, coupler, jobs, scheduler). Returns True if all exited with 0."""
    jobs = args.jobs or runs.default_jobs(args.case, args.set, args.coupler)
    runs.side_by_side(jobs)
    # Seed by seed: the first seed's whole curve is done before the second seed starts.
    pending = [(v, s) for s in (seeds or [None]) for v in values]
    campaign.write_plan(args.out, args.case, name, values, seeds, args.set, args.scheduler)

    def command(value, seed):
        d = campaign.run_dir(args.out, name, value, seed)
        return runs.command(args.case, d, campaign.run_sets(args.set, name, value, seed),
                            args.coupler)

    done = [k for k in pending
            if campaign.earlier_run(campaign.run_dir(args.out, name, *k), command(*k)) == "done"]
    if done:
        print(f"sweep: {len(done)} of {len(pending)} runs completed earlier; not run again",
              flush=True)
        pending = [k for k in pending if k not in done]
    print(f"sweep: {len(pending)} runs of {args.case} ({name} = {', '.join(values)}"
          + ("" if seeds is None else f"; seeds {', '.join(map(str, seeds))}")
          + f"), {jobs} at a time, into {args.out}", flush=True)
    running = {}  # (value, seed) -> (proc, log, t0, cmd)
    all_ok = True

    def stop(signum, frame):  # `kill` of the sweep stops its runs as Ctrl-C does
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    try:
        while pending or running:
            while pending and len(running) < jobs:
                key = pending.pop(0)
                running[key] = start_run(args, name, *key)
            time.sleep(0.2)
            for key in [k for k, r in running.items() if r[0].poll() is not None]:
                all_ok = finish_run(args, name, *key, *running.pop(key)) and all_ok
    except KeyboardInterrupt:
        # Ask the runs to stop (the coupler closes its output on SIGTERM), then insist.
        print(f"sweep: interrupted; stopping {len(running)} run(s)", file=sys.stderr)
        for proc, *_ in running.values():
            proc.send_signal(signal.SIGTERM)
        for proc, log, *_ in running.values():
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            log.close()
        raise SystemExit(130)
    return all_ok
