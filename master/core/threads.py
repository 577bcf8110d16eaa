"""One BLAS thread for every computation of rotorcosim, whatever the program imported first.

``rotorcosim/__init__.py`` sets ``OPENBLAS_NUM_THREADS=1`` before numpy loads OpenBLAS, but a program that
imported numpy first already has a pool of one thread per core. A multi-threaded BLAS sums in another order
(the rotor's eigen-solves and reductions, components/rotor/mta.py): measured, a 2 ms run of the shipped case after
``import numpy`` on 2 cores differed from the CLI's by up to 1e-5 relative in the recorded signals (values
near zero), so one scenario gave two answers. :func:`one_thread` limits every BLAS/OpenMP pool of the process
to one thread while it is entered (threadpoolctl, which changes the libraries' own setting at run time) and puts
back what was there on exit, so the caller's own work keeps its threads. It also wins over an
``OPENBLAS_NUM_THREADS`` the user set: a result must not depend on it. The small matrices of the model (tens to
hundreds of DOF) gain nothing from threads (measured 10 times slower eigen-solves on a loaded 2-core machine).

Entered by every entry point: the command line (cli.main), the API's simulate (so the Dask sweep workers too).
The exported FMUs cannot import rotorcosim; their slave (fmus/slave_template.py) does the same by itself.
"""
from __future__ import annotations

import contextlib

try:
    from threadpoolctl import threadpool_limits
except ImportError:  # an environment installed without the dependencies (pip --no-deps): the env default only
    threadpool_limits = None


@contextlib.contextmanager
def one_thread():
    """Within: every BLAS and OpenMP pool loaded in the process runs one thread (restored on exit). Nests.
    Without threadpoolctl installed (a dependency of the package) only OPENBLAS_NUM_THREADS=1 acts, which a
    program that imported numpy first defeats (tests/reliability/test_determinism.py then fails)."""
    if threadpool_limits is None:
        yield
        return
    with threadpool_limits(limits=1):
        yield
