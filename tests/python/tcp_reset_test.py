#!/usr/bin/python3
"""A TCP reset in the middle of a tcp run: the coupler and a module started by hand talk through a
relay that, once the run is under way, closes both of its connections with a reset (SO_LINGER 0).
The coupler must name the dropped connection with exit 3 within seconds, not wait out its
coupling timeout (60 s here) and then blame a module that is alive; the module must end its
session (exit 3) instead of staying up, owned by a dead session, refusing every other coupler.
About 10 s.

  tests/python/tcp_reset_test.py --coupler build/bin/coupler --tmp DIR
"""
import os
import shutil
import socket
import struct
import subprocess
import threading
import time
import unittest

import harness  # tests/python/harness.py: the command line
from rockcut import runs

ARGS = None
TIMEOUT_S = 60


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class ResettingRelay:
    """Forwards one connection from `listen_port` to `target_port` until reset() closes both ends
    with an RST."""

    def __init__(self, listen_port, target_port):
        self.server = socket.socket()
        self.server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.server.bind(("127.0.0.1", listen_port))
        self.server.listen(4)
        self.target_port = target_port
        self.pairs = []
        self.bytes = 0
        threading.Thread(target=self.accept, daemon=True).start()

    def accept(self):
        while True:
            try:
                client, _ = self.server.accept()
            except OSError:
                return
            upstream = socket.create_connection(("127.0.0.1", self.target_port))
            self.pairs.append((client, upstream))
            for a, b in ((client, upstream), (upstream, client)):
                threading.Thread(target=self.pump, args=(a, b), daemon=True).start()

    def pump(self, source, sink):
        try:
            while True:
                data = source.recv(65536)
                if not data:
                    return
                self.bytes += len(data)
                sink.sendall(data)
        except OSError:
            return

    def reset(self):
        self.server.close()  # the coupler's reconnection finds no one
        for pair in self.pairs:
            for s in pair:
                s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
                # shutdown() wakes the pump blocked in recv() on it; a bare close() would leave
                # the kernel socket open until that recv returned.
                try:
                    s.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass
                s.close()


class TcpReset(unittest.TestCase):
    def test_reset_is_named_at_once_and_the_module_ends_its_session(self):
        work = os.path.join(ARGS.tmp, "tcp_reset")
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        module_port, relay_port = free_port(), free_port()
        dem_module = os.path.join(os.path.dirname(os.path.abspath(ARGS.coupler)), "dem_module")
        module = subprocess.Popen([dem_module, "--bind", f"tcp://127.0.0.1:{module_port}"],
                                  cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True)
        try:
            time.sleep(0.3)  # bound before the relay connects to it
            relay = ResettingRelay(relay_port, module_port)
            scene = runs.case("cutting", "dry_reduced.pbtxt")
            coupler = subprocess.Popen(
                [ARGS.coupler, "run", scene, "--out", os.path.join(work, "out"), "--transport",
                 "tcp", "--dem-endpoint", f"tcp://127.0.0.1:{relay_port}", "--no-checkpoints",
                 "--set", f"coupling.timeout_s={TIMEOUT_S}",
                 # A slow tool: the same cut over 0.35 s, 5 times the steps of the scene's
                 # (20 s or more), so the reset comes well before the end.
                 "--set", "dem.tool.velocity_m_s=0.2", "--set", "time.end_time_s=0.35"],
                cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            # Under way: the handshake and Init passed (their messages carry the particles'
            # arrays, tens of kB), then a second of stepping. Waits on progress, not on the clock,
            # so a busy machine only makes it slower.
            deadline = time.monotonic() + 120
            while relay.bytes < 20000 and coupler.poll() is None and time.monotonic() < deadline:
                time.sleep(0.05)
            time.sleep(1.0)
            self.assertGreater(relay.bytes, 0)
            self.assertIsNone(coupler.poll(), "the run ended before the reset")
            reset_at = time.monotonic()
            relay.reset()
            out, err = coupler.communicate(timeout=TIMEOUT_S + 30)
            named_after_s = time.monotonic() - reset_at
            self.assertEqual(coupler.returncode, 3, err)
            self.assertIn("dropped", err)
            self.assertIn(f"tcp://127.0.0.1:{relay_port}", err)
            self.assertEqual(err.count("error:"), 1, err)
            self.assertLess(named_after_s, 10.0, f"named after {named_after_s:.1f} s: {err}")
            # The module ends the session whose connection dropped, saying why.
            _, module_err = module.communicate(timeout=20)
            self.assertEqual(module.returncode, 3, module_err)
            self.assertIn("session ended", module_err)
        finally:
            if module.poll() is None:
                module.kill()
                module.wait()


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
