"""Studies over many runs of a scenario: model updating against measured results and uncertainty quantification.

A layer above the API (:mod:`rotorcosim.master.api`) and below the command line; its modules:

================  ==========================================================================================
``spec``          the SPEC files of ``calibrate`` and ``uq`` (TOML), read and checked before anything runs
``targets``       ``targets.csv`` (measured values), results read from a run's summary, residuals, scores
``evaluate``      runs of the scenario with overrides in parallel on Dask (local or a running cluster), or serially
``store``         every finished run kept in a CSV table as it finishes, read back on resume
``statistics``    standard errors and correlations of a fit, moments and percentiles with intervals, Sobol'
``calibration``   :func:`calibrate`: bounded nonlinear least squares (scipy's trust-region reflective)
``uncertainty``   :func:`uq`: Monte Carlo, Latin hypercube or Saltelli / Sobol' samples, SALib indices
``figures``       the PNG figures of both
================  ==========================================================================================

::

    import rotorcosim
    rotorcosim.calibrate("calibrate.toml", "calibration_out")   # rotorcosim calibrate calibrate.toml --out DIR
    rotorcosim.uq("uq.toml", "uq_out")                         # rotorcosim uq uq.toml --out DIR
"""
_PUBLIC = {"calibrate": "rotorcosim.master.study.calibration", "uq": "rotorcosim.master.study.uncertainty"}

__all__ = sorted(_PUBLIC)


def __getattr__(name):
    if name in _PUBLIC:
        import importlib

        return getattr(importlib.import_module(_PUBLIC[name]), name)
    raise AttributeError(f"module 'rotorcosim.master.study' has no attribute {name!r}")
