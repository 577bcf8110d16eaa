"""The co-simulation master: it steps a system of components through a schedule and records what happens.

Sub-packages, lowest layer first (``manipulator``, ``observer`` and ``compiled`` are one layer of independent
siblings, as are ``run`` and ``case``); a module imports only from its own layer or the layers below it (checked by
the import-linter contract in ``pyproject.toml``, run by ``tests/test_architecture.py``):

============================  ===========================================================================
``core``                      a system of components and connections (checked when built), the links that
                              carry values between them (one semantics for both loops), the stepping
                              algorithms (Gauss-Seidel, Jacobi), the cycle a run counts its windows in, the
                              phases a scenario declares (its names of the coupled and the held phase)
``manipulator``               the staggered scheme's hold of the held phase (freeze, held values, restart)
``observer``                  recorder (``timeseries.h5``), progress, steady windows, energy; they never
                              change a run
``compiled``                  the optional fast path for thermo-mechanical intervals (numba kernels)
``schedule``                  timelines of coupled / held intervals (thermo-mechanical / thermal-only), the
                              automatic schedule, the time budget
``simulation`` (module)       :class:`~rotorcosim.master.simulation.Simulation`: runs a system through a
                              schedule with its observers and hold
``scenario``                  scenarios as data: TOML / SSP, schema checks, ``extends``, ``--set`` / ``--swap``
``run``                       run folders, checkpoints and resume, watchdog, figure workers
``case`` (module)             how a case (results, figures, commands of a study) plugs in
``api`` (module)              the Python API: :func:`load_scenario`, :func:`simulate`, :class:`Result`
``sweep``                     many cases on Dask into one folder (:func:`~rotorcosim.master.sweep.run_cases`):
                              the lock, each case's folder whole, resume, what it does under faults
``study``                     calibration and uncertainty quantification over many runs, stored and resumed
``compare``                   any scenario run staggered and monolithic, timed and tabulated
                              (:func:`~rotorcosim.master.compare.compare_schemes`)
``cli``                       the ``rotorcosim`` program, a thin layer over the API
============================  ===========================================================================

Below the master: ``rotorcosim.components`` (the physics; it imports nothing of the master) and
``rotorcosim.fmus`` (the FMI boundary: FMUs as components, components as FMUs). Above it: ``rotorcosim.cases``
(the shipped cases), which plug in as a user's case would (``master.case``).

The public names, importable from here (loaded on first use)::

    from rotorcosim.master import load_scenario, simulate
    res = simulate(load_scenario("toy_thermomechanical"), duration=0.05)
    res["node.T"], res.summary
"""
_PUBLIC = {
    "load_scenario": "rotorcosim.master.api",
    "simulate": "rotorcosim.master.api",
    "Result": "rotorcosim.master.api",
    "Scenario": "rotorcosim.master.scenario.build",
    "SimulationDiverged": "rotorcosim.master.core.algorithm",
    "Simulation": "rotorcosim.master.simulation",
    "System": "rotorcosim.master.core.system",
    "Observer": "rotorcosim.master.observer.observer",
    "Case": "rotorcosim.master.sweep",
    "run_cases": "rotorcosim.master.sweep",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name):
    if name in _PUBLIC:
        import importlib

        return getattr(importlib.import_module(_PUBLIC[name]), name)
    raise AttributeError(f"module 'rotorcosim.master' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
