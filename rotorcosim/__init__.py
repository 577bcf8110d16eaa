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

The code lives in the top-level folders fixed by the design card and is installed as sub-packages:
``rotorcosim.components`` (components/), ``rotorcosim.master`` (master/), ``rotorcosim.fmus`` (fmus/).
"""
import os as _os

__version__ = "0.1.0"

# The model's matrices are small (tens to hundreds of DOF): a multi-threaded BLAS only adds contention, and on a
# loaded 2-core machine it made the rotor's eigen-solves 10 times slower (measured). Set before numpy loads it;
# a value the user has set wins.
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# Running from a source checkout (``python -m pytest`` puts the checkout first on sys.path) this folder
# shadows the installed package; let the sub-packages resolve to the sibling folders in that case.
_checkout = _os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))
if _os.path.isfile(_os.path.join(_checkout, "components", "contract.py")):
    __path__.append(_checkout)  # noqa: F821  (module attribute of a package)

#: the API, imported on first use so that ``rotorcosim --help`` and the light commands start fast
_API = ("load_scenario", "simulate", "Result", "Scenario", "SimulationDiverged")
#: the studies over many runs (master/study/), imported on first use too
_STUDIES = ("calibrate", "uq")


def __getattr__(name):
    if name in _API:
        from rotorcosim.master import api

        return getattr(api, name)
    if name in _STUDIES:
        from rotorcosim.master import study

        return getattr(study, name)
    raise AttributeError(f"module 'rotorcosim' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + list(_API) + list(_STUDIES))
