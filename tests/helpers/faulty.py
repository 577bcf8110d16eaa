"""A thermal node that misbehaves on purpose, and a real Dask cluster of separate processes, for the fault tests.

``FaultyNode`` is the toy's ``testing.thermal_node`` (components/testing/thermo_toy.py) with faults switched on
by parameters, each from the simulated time given (s; negative: never):

- ``kill_at``: the process running it kills itself (SIGKILL, as the kernel's OOM killer or a crash in native
  code would end it); with ``marker`` (a file path) only the first time, creating the file: the retry succeeds;
- ``raise_at``: ``do_step`` raises a RuntimeError (a component's own exception);
- ``nan_at``: its temperature becomes NaN (a real divergence);
- ``sleep``: wall seconds slept in each step (a slow case, to interrupt or kill mid-way);
- ``hold`` (a file path): each step waits until that file exists (a case held open until the test releases it,
  whatever the machine's load);
- ``started`` (a file path): the first step of each instance appends a line to that file (the test knows how many
  cases are under way without guessing from the time).

The scenario :func:`scenario` writes is the toy's with this node in place of ``node``.
"""
from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from rotorcosim import scenarios
from rotorcosim.components.contract import Variable
from rotorcosim.components.testing.thermo_toy import ThermalNode

TOY = Path(scenarios.__file__).with_name("toy_thermomechanical.toml")


class FaultyNode(ThermalNode):
    description = "the toy's thermal node, with faults switched on by parameters (tests only)"
    variables = ThermalNode.variables + (
        Variable("kill_at", "parameter", unit="s", start=-1.0),
        Variable("raise_at", "parameter", unit="s", start=-1.0),
        Variable("nan_at", "parameter", unit="s", start=-1.0),
        Variable("sleep", "parameter", unit="s", start=0.0),
        Variable("marker", "parameter", type="String", start=""),
        Variable("hold", "parameter", type="String", start=""),
        Variable("started", "parameter", type="String", start=""),
    )

    #: the longest a held step waits for its file (s): a test that fails never leaves a process behind for good
    HOLD_LIMIT = 300.0

    def do_step(self, t, h):
        p = self.p
        if p["started"] and not getattr(self, "_announced", False):
            self._announced = True
            with open(p["started"], "a") as f:
                f.write(f"{os.getpid()}\n")
        if p["hold"]:
            deadline = time.monotonic() + self.HOLD_LIMIT
            while not os.path.exists(p["hold"]) and time.monotonic() < deadline:
                time.sleep(0.01)
        if p["sleep"] > 0:
            time.sleep(p["sleep"])
        if 0 <= p["kill_at"] <= t:
            marker = p["marker"]
            if not marker or not os.path.exists(marker):
                if marker:
                    Path(marker).write_text(str(os.getpid()))
                os.kill(os.getpid(), signal.SIGKILL)
        if 0 <= p["raise_at"] <= t:
            raise RuntimeError("the faulty node's own error")
        super().do_step(t, h)
        if 0 <= p["nan_at"] <= t:
            self.y["T"] = np.array([float("nan")])


def scenario(folder: Path, **faults) -> Path:
    """A scenario file in ``folder``: the toy with ``node`` a FaultyNode with ``faults`` as its parameters."""
    params = {"C": 10.0, "R": 1.0, **faults}
    text = ", ".join(f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"' for k, v in params.items())
    f = folder / "faulty.toml"
    f.write_text(f'[scenario]\nextends = "{TOY}"\nname = "faulty"\n\n[components.node]\n'
                 f'implementation = "tests.helpers.faulty:FaultyNode"\nparameters = {{ {text} }}\n')
    return f


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Cluster:
    """``dask scheduler`` and ``n`` ``dask worker`` processes (each with a nanny that restarts it, one thread)
    on loopback, each worker in a folder of its own under ``root``; ``stop()`` kills what is left."""

    def __init__(self, root: Path, n: int = 2, timeout: float = 60.0):
        self.root = root
        self.port = free_port()
        self.address = f"tcp://127.0.0.1:{self.port}"
        # the workers import the faulty plug-in (tests.helpers.faulty) from this checkout, as a user's workers
        # import their plug-ins from where they are installed
        checkout = str(Path(__file__).resolve().parents[2])
        path = os.pathsep.join(p for p in (checkout, os.environ.get("PYTHONPATH", "")) if p)
        env = {**os.environ, "PYTHONUNBUFFERED": "1", "PYTHONPATH": path}
        # the scheduler reruns no task whose worker died: every death reaches the client, which retries and reports
        # it (master/sweep/retry.py), as on the local cluster
        self.scheduler = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port",
             str(self.port), "--no-dashboard"], cwd=root,
            env={**env, "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0"}, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL, start_new_session=True)
        self.workers = []
        for i in range(n):
            wdir = root / f"worker{i}"
            wdir.mkdir(exist_ok=True)
            self.workers.append(subprocess.Popen(
                [sys.executable, "-m", "distributed.cli.dask_worker", self.address, "--nthreads", "1",
                 "--nworkers", "1", "--no-dashboard", "--local-directory", str(wdir), "--name", f"w{i}"],
                cwd=wdir, env={**env, "TMPDIR": str(wdir)}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                start_new_session=True))
        try:
            self.wait_for(n, timeout)
        except BaseException:
            self.stop()
            raise

    def wait_for(self, n: int, timeout: float) -> None:
        from dask.distributed import Client

        deadline = time.monotonic() + timeout
        while True:
            try:
                with Client(self.address, timeout=5) as c:
                    if len(c.scheduler_info()["workers"]) >= n:
                        return
            except OSError:
                pass
            if time.monotonic() > deadline:
                raise TimeoutError(f"the Dask scheduler and {n} workers did not come up within {timeout} s")
            time.sleep(0.3)

    def kill_scheduler(self) -> None:
        """SIGKILL the scheduler (its process group: the scheduler alone)."""
        _killpg(self.scheduler)

    def stop(self) -> None:
        """SIGKILL every process left: each worker's nanny with its worker process (one process group each),
        the scheduler."""
        for p in [*self.workers, self.scheduler]:
            _killpg(p)
        for p in [*self.workers, self.scheduler]:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                pass


def _killpg(p: subprocess.Popen) -> None:
    try:
        os.killpg(p.pid, signal.SIGKILL)   # the group this test started (start_new_session), nothing else
    except ProcessLookupError:
        pass
