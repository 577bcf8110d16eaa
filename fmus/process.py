"""An FMU run in a process of its own: a crash or a hang of the FMU fails the run cleanly instead of taking the
host down or hanging it.

:class:`ProcessFMU` follows the component contract in the master's process and forwards every call to an
:class:`~rotorcosim.fmus.importer.FMUComponent` living in a child process (a fresh interpreter started with
``subprocess``, talking over a socket pair: nothing of the host's state is shared, and unlike multiprocessing's
spawn it does not re-run the user's script, so no ``if __name__ == "__main__"`` guard is needed). Each call waits at most ``timeout`` seconds (the FMU step time limit): a call that
does not return in time kills the child and raises :class:`FMUError` naming the FMU, the call and the time; a child
that dies (a segfault in the FMU's binary) raises one naming the signal. The price is one pipe round trip per
call (some tens of microseconds), hence an option (``process = true`` on a scenario's FMU component, or
``rotorcosim run --fmu-process``).

FMU states stay in the child: ``get_state`` returns a handle valid for this run only (rollback works; a
checkpoint on disk cannot hold it and says so).
"""
from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
from multiprocessing.connection import Connection
from typing import Any, Mapping

from rotorcosim.components.contract import Component, StopRequested

from rotorcosim.components.errors import ProcessDied, StepTimeout
from rotorcosim.fmus.importer import FMUError


class FMUStepTimeout(FMUError, StepTimeout):
    """A call into the FMU's process did not return within the step time limit (the process was stopped)."""


class FMUProcessDied(FMUError, ProcessDied):
    """The FMU's process died during a call (a crash in the FMU's binary, a kill)."""

#: the default FMU step time limit (s): generous, a doStep of our FMUs takes microseconds to milliseconds
STEP_TIMEOUT_S = 600.0


def load_fmu(path: str, name: str, parameters: dict, start: dict):
    from rotorcosim.fmus.importer import FMUComponent

    return FMUComponent(path, name, parameters, start)


def _child(fd: int) -> None:
    """The child process's entry point: the connection on ``fd``, then the component it is asked for."""
    conn = Connection(fd)
    factory, path, name, parameters, start = conn.recv()
    _serve(conn, factory, path, name, parameters, start)


def _serve(conn, factory, path: str, name: str, parameters: dict, start: dict) -> None:
    """The child: builds the component (``factory(path, name, parameters, start)``: the FMU) and answers the
    parent's calls until told to stop."""
    try:
        comp = factory(path, name, parameters, start)
    except Exception as exc:
        conn.send(("error", f"{type(exc).__name__}: {exc}"))
        return
    states: dict[int, Any] = {}
    conn.send(("ok", {"variables": comp.variables, "phases": comp.phases, "preferred_step": comp.preferred_step,
                      "description": comp.description, "p": comp.p, "explicit": comp.explicit,
                      "can_get_set_state": getattr(comp, "can_get_set_state", True)}))
    while True:
        try:
            call, args = conn.recv()
        except EOFError:
            return
        try:
            if call == "setup":
                t0, u = args
                comp.u.update(u)          # the constant inputs given before set-up enter initialisation
                comp.setup(t0)
                out = (comp.y, comp.phases, comp.holds_state_in_TO)
            elif call == "step":
                u, t, h = args
                comp.u.update(u)
                comp.do_step(t, h)
                out = comp.y
            elif call == "phase":
                comp.enter_phase(*args)
                out = None
            elif call == "get_state":
                states[len(states)] = comp.get_state()
                out = len(states) - 1
            elif call == "set_state":
                comp.set_state(states[args[0]])
                out = comp.y
            elif call == "terminate":
                comp.terminate()
                conn.send(("ok", None))
                return
            else:
                raise ValueError(f"unknown call {call!r}")
        except StopRequested as req:   # the FMU asked to stop: an answer with its outputs there, not an error
            conn.send(("stop", (comp.y, req.t_stop, req.reason)))
            continue
        except Exception as exc:
            conn.send(("error", f"{type(exc).__name__}: {exc}" if not isinstance(exc, FMUError) else str(exc)))
            continue
        conn.send(("ok", out))


class _RemoteState:
    """A handle to an FMU state kept in the FMU's process."""

    def __init__(self, index: int, time: float, u: dict, y: dict):
        self.index, self.time, self.u, self.y = index, time, u, y

    def __reduce__(self):
        raise TypeError("an FMU state lives in the FMU's process and cannot be written to disk")


class ProcessFMU(Component):
    """An FMU as a component, run in a child process with a time limit on every call."""

    def __init__(self, path, name: str = "component", parameters: Mapping[str, Any] | None = None,
                 timeout: float = STEP_TIMEOUT_S, factory=load_fmu, start: Mapping[str, Any] | None = None,
                 label: str | None = None):
        if not (timeout > 0):
            raise FMUError(f"FMU {label or path} (component {name!r}): step time limit must be positive, got "
                           f"{timeout}")
        self.path = str(path)
        self._label = label
        self.name = name
        self.timeout = float(timeout)
        self._where = f"FMU {label or path} (component {name!r}, in its own process)"
        ours, theirs = socket.socketpair()
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
        self._proc = subprocess.Popen(
            [sys.executable, "-c", "import sys; from rotorcosim.fmus.process import _child; _child(int(sys.argv[1]))",
             str(theirs.fileno())], pass_fds=(theirs.fileno(),), env=env)
        theirs.close()
        self._conn = Connection(ours.detach())
        self._conn.send((factory, self.path, name, dict(parameters or {}), dict(start or {})))
        # loading takes seconds (a fresh interpreter, imports, extraction): the generous default limit at least
        try:
            info = self._call(None, (), "loading", max(self.timeout, STEP_TIMEOUT_S))
        except BaseException:  # the child is stopped and reaped now (it was left "still running" to the collector)
            self._kill()
            raise
        self.variables = tuple(info["variables"])
        self._by_name = {v.name: v for v in self.variables}
        self.phases = info["phases"]
        self.preferred_step = info["preferred_step"]
        self.description = info["description"]
        self.p = info["p"]
        self.explicit = set(info["explicit"])
        self.can_get_set_state = info["can_get_set_state"]
        self.holds_state_in_TO = False
        self.phase = None
        self.u = {v.name: v.start_array() for v in self.variables if v.causality == "input" and v.carried}
        self.y = {v.name: v.start_array() for v in self.variables if v.causality == "output" and v.carried}
        self.state = {}
        self.time = 0.0

    def _call(self, call: str | None, args: tuple, what: str, timeout: float | None = None):
        timeout = self.timeout if timeout is None else timeout
        try:
            if call is not None:
                self._conn.send((call, args))
            ready = self._conn.poll(timeout)
            if not ready:
                self._kill()
                raise FMUStepTimeout(f"{self._where}: {what} did not return within {timeout:g} s (the FMU step "
                               "time limit): the FMU was stopped")
            status, value = self._conn.recv()
        except (EOFError, BrokenPipeError, ConnectionResetError, OSError):
            try:
                code = self._proc.wait(5)
            except subprocess.TimeoutExpired:
                code = None
            how = (f"killed by {signal.Signals(-code).name}" if code is not None and code < 0
                   else f"exit status {code}")
            raise FMUProcessDied(f"{self._where}: the FMU's process died in {what} ({how})") from None
        if status == "error":
            if self._label:   # the child names the temporary file it loaded
                value = str(value).replace(f"FMU {self.path}", f"FMU {self._label}")
            raise FMUError(f"{self._where}: {what} failed: {value}")
        if status == "stop":
            self.y, self.time, reason = value
            raise StopRequested(self.name, self.time, reason)
        return value

    def _kill(self) -> None:
        if self._proc.poll() is None:
            self._proc.kill()
        try:
            self._proc.wait(5)
        except subprocess.TimeoutExpired:
            pass
        self._conn.close()

    # -- the contract --------------------------------------------------------------------------------
    def set_parameter(self, name: str, value: Any) -> None:
        raise FMUError(f"{self._where}: parameters are given when the FMU is loaded")

    def setup(self, t0: float = 0.0) -> None:
        self.time = float(t0)
        y, self.phases, self.holds_state_in_TO = self._call("setup", (t0, self.u), "setup")
        self.y = y

    def enter_phase(self, phase: str) -> None:
        self.phase = phase
        self._call("phase", (phase,), "enter_phase")

    def do_step(self, t: float, h: float) -> None:
        self.y = self._call("step", (self.u, t, h), f"DoStep(t = {t:.9g} s, h = {h:.3g} s)")
        self.time = t + h

    def get_state(self) -> Any:
        index = self._call("get_state", (), "get_state")
        return _RemoteState(index, self.time, {k: v.copy() for k, v in self.u.items()},
                            {k: v.copy() for k, v in self.y.items()})

    def set_state(self, snapshot: Any) -> None:
        self._call("set_state", (snapshot.index,), "set_state")
        self.time = snapshot.time
        self.u = {k: v.copy() for k, v in snapshot.u.items()}
        self.y = {k: v.copy() for k, v in snapshot.y.items()}

    def terminate(self) -> None:
        if self._proc.poll() is None:
            try:
                self._call("terminate", (), "terminate")
            except FMUError:
                pass
        self._kill()

    def __del__(self):
        proc = getattr(self, "_proc", None)
        if proc is not None and proc.poll() is None:
            proc.kill()
            try:
                proc.wait(1)
            except subprocess.TimeoutExpired:
                pass

    def __repr__(self) -> str:
        return f"<ProcessFMU {self.name!r} from {self.path}>"
