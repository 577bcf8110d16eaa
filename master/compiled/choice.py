"""The engine choice of a thermo-mechanical interval, decided without importing numba: the compiled loop
(:mod:`.runner`, which needs numba) is imported only for an interval it can run, so that a system of FMUs or
Python plug-ins never imports numba."""
from __future__ import annotations

import numpy as np

from rotorcosim.components.contract import COUPLED, ContractError
from rotorcosim.components.kernels import KernelComponent

from rotorcosim.master.core.algorithm import GaussSeidel

#: the engines of ``Simulation.engine_choice`` (``--engine``)
ENGINES = ("auto", "python", "compiled")


class CompiledUnavailable(ContractError):
    """``--engine compiled`` asked for an interval the compiled path cannot run (the message says why)."""


def class_why_not(name: str, cls: type) -> str | None:
    """The reason component ``name``, of class ``cls``, can run no thermo-mechanical interval compiled, or None
    (whether an interval can is :func:`why_not`'s to say, once the system is built)."""
    if not (isinstance(cls, type) and issubclass(cls, KernelComponent)) or cls.STEP is None:
        return f"component {name} ({getattr(cls, '__name__', cls)}) has no compiled kernel"
    return None


def check_request(reasons: dict[str, str], choice: str) -> None:
    """Refuse ``--engine compiled`` before the run starts when a component taking part in its thermo-mechanical
    intervals can never run compiled (``reasons``: :func:`class_why_not` of each, from the scenario's classes):
    without it the run printed its estimate, built the system and started before the first interval refused."""
    if reasons:
        refuse(None, choice, next(iter(reasons.values())))


def why_not(sim, active, mult, stop) -> str | None:
    """None when the interval can run compiled, else the reason it cannot."""
    comps = sim.system.components
    for n in active:
        c = comps[n]
        if (reason := class_why_not(n, type(c))) is not None:
            return reason
        if c.event_indicators and not c.KERNEL_EVENTS:
            return (f"component {n} declares event indicators and its kernel does not report their changes of "
                    "sign (KERNEL_EVENTS), so the generic loop locates them (master/core/events.py)")
        if not c.kernel_available():
            return f"component {n} has no compiled kernel in this phase"
        for port in c.kernel_ports()[3]:  # outputs become views of the loop's float array
            if np.asarray(c.y[port]).dtype != np.float64:
                return f"output {n}.{port} is not a float array"
    eng = sim.engine
    s = eng.settings
    if type(eng.algorithm) is not GaussSeidel or s.iterations != 1:
        return f"the {s.algorithm} algorithm with {s.iterations} iteration(s) (compiled: Gauss-Seidel, 1 iteration)"
    for link in eng.links:
        d, src = link.con.dst_component, link.con.src_component
        if d not in mult:
            continue
        if src not in mult:
            return f"{link.con.src} -> {link.con.dst}: its producer does not step in this interval"
        if link.conv is not None or not link.real:
            return f"{link.con.src} -> {link.con.dst}: a converted or non-Real connection"
        if link.held is not None or link.frozen is not None:
            return f"{link.con.src} -> {link.con.dst}: held by the master"
    for link in eng.links:
        if link.window is not None and link.con.src_component in mult:
            src = comps[link.con.src_component]
            if any(src.variable(p).type != "Real" for p in link.window.ports):
                return f"{link.con.src}: its hand-off window records non-Real inputs"
    for obs in sim.observers:
        if obs.block_signals(sim) is None:
            return f"observer {type(obs).__name__} has no step_block"
    return None


def runner(sim, phase, active, mult, step, stop, choice: str):
    """A compiled runner for this interval (master/compiled/runner.Runner), or None for the generic loop (the
    reason in sim.engine_note); with ``choice`` "compiled", CompiledUnavailable instead of None."""
    if choice == "python" or phase != COUPLED:
        return None
    reason = why_not(sim, active, mult, stop)
    if reason is not None:
        return refuse(sim, choice, reason)
    from rotorcosim.master.compiled import runner as compiled

    r = compiled.runner(sim, active, mult, step, stop)
    return refuse(sim, choice, r) if isinstance(r, str) else r


def refuse(sim, choice, reason):
    """No compiled runner: an error under ``--engine compiled``, else the reason noted for the summary (``sim``
    None: before the run, nothing to note)."""
    if choice == "compiled":
        raise CompiledUnavailable(f"--engine compiled: cannot compile the thermo-mechanical interval: {reason}")
    if sim is not None:
        sim.engine_note = reason
    return None
