"""A single-node Slurm cluster of its own, for tests: munged, slurmctld and slurmd from Debian's
packages, started as root in a temporary directory with their own configuration, socket and
ports, and stopped by pid at the end, whatever happens.

    with SlurmCluster(tmp) as cluster:      # raises Unavailable with the reason if it cannot start
        subprocess.run(["sbatch", ...], env=cluster.env)
"""
import os
import pwd
import shutil
import signal
import socket
import subprocess
import time

DAEMONS = {"munged": "/usr/sbin/munged", "slurmctld": "/usr/sbin/slurmctld",
           "slurmd": "/usr/sbin/slurmd"}
CLIENTS = ["sbatch", "squeue", "scontrol", "sinfo"]


class Unavailable(Exception):
    """The cluster cannot be started here (not root, packages missing): the test is skipped."""


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _exit_on_sigterm(signum, frame):
    raise SystemExit(128 + signum)


class SlurmCluster:
    def __init__(self, root, cpus=None):
        self.root = os.path.abspath(root)
        self.cpus = cpus or os.cpu_count() or 1
        self.pids = {}
        self.env = dict(os.environ)

    # --- start and stop -----------------------------------------------------------------------

    def __enter__(self):
        if os.geteuid() != 0:
            raise Unavailable("the daemons run as root (SlurmUser=root) and this test is not root")
        missing = [p for p in DAEMONS.values() if not os.access(p, os.X_OK)]
        missing += [c for c in CLIENTS if shutil.which(c) is None]
        if missing:
            raise Unavailable("not installed: " + ", ".join(missing) +
                              " (scripts/setup installs slurmctld, slurmd, slurm-client, munge)")
        try:
            pwd.getpwnam("munge")
        except KeyError:
            raise Unavailable("no munge user (the munge package creates it)")
        # A test stopped with SIGTERM (ctest's timeout, a user's kill) unwinds through __exit__
        # instead of leaving the daemons running.
        signal.signal(signal.SIGTERM, _exit_on_sigterm)
        try:
            self._start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc):
        self.stop()
        return False

    def _start(self):
        if os.path.exists(self.root):
            shutil.rmtree(self.root)
        munge_dir = os.path.join(self.root, "munge")
        for d in ("state", "spool", "log", "munge"):
            os.makedirs(os.path.join(self.root, d))
        munge = pwd.getpwnam("munge")
        os.chmod(self.root, 0o755)
        os.chown(munge_dir, munge.pw_uid, munge.pw_gid)
        os.chmod(munge_dir, 0o755)
        # A key of the cluster's own, readable by munge only.
        key = os.path.join(munge_dir, "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chown(key, munge.pw_uid, munge.pw_gid)
        os.chmod(key, 0o400)
        self.munge_socket = os.path.join(munge_dir, "munge.sock")
        r = subprocess.run(["runuser", "-u", "munge", "--", DAEMONS["munged"],
                            "--socket=" + self.munge_socket, "--key-file=" + key,
                            "--pid-file=" + os.path.join(munge_dir, "munged.pid"),
                            "--log-file=" + os.path.join(munge_dir, "munged.log"),
                            "--seed-file=" + os.path.join(munge_dir, "munged.seed")],
                           capture_output=True, text=True)
        if r.returncode != 0:  # e.g. a parent directory the munge user cannot enter
            raise Unavailable("munged did not start: " + (r.stderr.strip() or r.stdout.strip()))
        self.pids["munged"] = self._read_pid(os.path.join(munge_dir, "munged.pid"))

        host = socket.gethostname()
        self.conf = os.path.join(self.root, "slurm.conf")
        with open(self.conf, "w") as f:
            f.write(f"""# A one-node test cluster (tests/slurm/slurm_cluster.py).
ClusterName=rockcut-test
SlurmctldHost={host}
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser=root
AuthType=auth/munge
# cred_expire: a requeued task may start again this long after its requeue (default 120 s).
AuthInfo=socket={self.munge_socket},cred_expire=10
CredType=cred/munge
StateSaveLocation={self.root}/state
SlurmdSpoolDir={self.root}/spool
SlurmctldPidFile={self.root}/slurmctld.pid
SlurmdPidFile={self.root}/slurmd.pid
SlurmctldLogFile={self.root}/log/slurmctld.log
SlurmdLogFile={self.root}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
# Builtin (FIFO): a task starts as soon as a CPU frees, not at the next backfill pass (30 s).
SchedulerType=sched/builtin
# A requeued task is held for cred_expire; the main loop then starts it within 2 s instead of at
# its next pass (30-60 s), which left the node idle when no other task was pending.
SchedulerParameters=sched_interval=2
MpiDefault=none
ReturnToService=2
JobRequeue=1
KillWait=10
MinJobAge=600
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName={host} CPUs={self.cpus} State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
""")
        self.env["SLURM_CONF"] = self.conf
        for daemon, pid_file in (("slurmctld", "slurmctld.pid"), ("slurmd", "slurmd.pid")):
            r = subprocess.run([DAEMONS[daemon], "-f", self.conf], capture_output=True, text=True,
                               env=self.env)
            if r.returncode != 0:
                raise Unavailable(f"{daemon} did not start: {r.stderr.strip()}")
            self.pids[daemon] = self._read_pid(os.path.join(self.root, pid_file))
        deadline = time.time() + 60
        while time.time() < deadline:
            r = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True,
                               env=self.env)
            if r.returncode == 0 and r.stdout.strip() == "idle":
                return
            time.sleep(0.5)
        raise Unavailable("the node did not become idle within 60 s: " + self.log_tail())

    def _read_pid(self, path, timeout=20):
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                with open(path) as f:
                    text = f.read().strip()
                if text:
                    return int(text)
            except FileNotFoundError:
                pass
            time.sleep(0.1)
        raise Unavailable(f"no pid file {path}")

    def stop(self):
        """Cancels this cluster's jobs, then stops exactly the daemons it started."""
        if "slurmctld" in self.pids:
            subprocess.run(["scancel", "--full", "--user=root"], env=self.env, capture_output=True)
            deadline = time.time() + 30
            while time.time() < deadline:
                r = subprocess.run(["squeue", "-h"], env=self.env, capture_output=True, text=True)
                if r.returncode != 0 or not r.stdout.strip():
                    break
                time.sleep(0.5)
        for name in ("slurmd", "slurmctld", "munged"):
            pid = self.pids.pop(name, None)
            if pid is None:
                continue
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                continue
            deadline = time.time() + 20
            while time.time() < deadline:
                try:
                    os.kill(pid, 0)
                except ProcessLookupError:
                    break
                time.sleep(0.1)
            else:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass

    def log_tail(self, lines=20):
        out = []
        for name in ("slurmctld.log", "slurmd.log"):
            try:
                with open(os.path.join(self.root, "log", name)) as f:
                    out.append(name + ":\n" + "".join(f.readlines()[-lines:]))
            except FileNotFoundError:
                pass
        return "\n".join(out)
