"""rotorcosim: co-simulation of a dual-rotor gas turbine engine during and after a blade-loss event.

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
