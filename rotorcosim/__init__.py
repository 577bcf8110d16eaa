"""rotorcosim: co-simulation of a dual-rotor gas turbine engine during and after a blade-loss event.

The Python API (``master/api.py``)::

    import rotorcosim
    sc = rotorcosim.load_scenario("blade_loss_2850")          # shipped name or path
    sc = sc.set({"rotor.F_unbalance": 5700.0})                 # returns a new scenario
    sc = sc.swap("damper0", "damper.fe")                       # registry name, "module:Class", or a .fmu path
    res = rotorcosim.simulate(sc, duration=0.05)               # schedule=..., out=DIR writes the CLI's files
    res.time, res.phase, res["bearing0.P_drag"], res.summary   # numpy arrays; summary as in summary.json
    df = res.to_dataframe()                                    # labelled columns with units (needs pandas)
    rotorcosim.calibrate("spec.toml", "out")                   # model updating (master/study/calibrate.py)
    rotorcosim.uq("uq.toml", "out")                            # uncertainty quantification (master/study/uq.py)

The code lives in the checkout's top-level folders and is installed as sub-packages:
``rotorcosim.components`` (components/), ``rotorcosim.master`` (master/), ``rotorcosim.fmus`` (fmus/).
"""
import os as _os

# Running from a source checkout (``python -m pytest`` puts the checkout first on sys.path) this folder
# shadows the installed package; let the sub-packages resolve to the sibling folders in that case.
_checkout = _os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))
_IN_CHECKOUT = _os.path.isfile(_os.path.join(_checkout, "components", "contract.py"))
if _IN_CHECKOUT:
    __path__.append(_checkout)  # noqa: F821 - __path__ is set by the import system on a package, unseen by ruff


def _version() -> str:
    """The version, written once in pyproject.toml: the checkout's own file when running from one (the installed
    copy may be another), else the installed distribution's metadata (tests/test_version.py: CITATION.cff too)."""
    if _IN_CHECKOUT:
        import re

        text = open(_os.path.join(_checkout, "pyproject.toml"), encoding="utf-8").read()
        return re.search(r'^version = "([^"]+)"', text, re.M).group(1)
    from importlib.metadata import version

    return version("rotorcosim")

#: the API, imported on first use so that ``rotorcosim --help`` and the light commands start fast
_API = ("load_scenario", "simulate", "Result", "Scenario", "SimulationDiverged")
#: the studies over many runs (master/study/), imported on first use too
_STUDIES = ("calibrate", "uq")


def __getattr__(name):
    if name == "__version__":
        globals()["__version__"] = v = _version()
        return v
    if name in _API:
        from rotorcosim.master import api

        return getattr(api, name)
    if name in _STUDIES:
        from rotorcosim.master import study

        return getattr(study, name)
    raise AttributeError(f"module 'rotorcosim' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + ["__version__", *_API, *_STUDIES])
