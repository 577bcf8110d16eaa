"""One BLAS thread for every computation of a run, whatever the program imported first.

Importing rotorcosim changes nothing in the process (no environment variable is set): numpy's OpenBLAS starts
with one thread per core, as in any program. A multi-threaded BLAS sums in another order (the rotor's eigen-solves
and reductions, components/rotor/mta.py): measured, a 2 ms run of the shipped case with OpenBLAS on 2 threads
differed from one on 1 thread by up to 1e-5 relative in the recorded signals (values near zero), so one scenario
gave two answers. :func:`one_thread` limits every BLAS/OpenMP pool of the process to one thread while it is
entered (threadpoolctl, which changes the libraries' own setting at run time) and puts back what was there on
exit, so the caller's own work keeps its threads. It also wins over an ``OPENBLAS_NUM_THREADS`` the user set: a
result must not depend on it. The small matrices of the model (tens to hundreds of DOF) gain nothing from threads
(measured 10 times slower eigen-solves on a loaded 2-core machine).

Entered by every entry point: the command line (cli.main), the API's simulate (so the Dask sweep workers too) and
draw_figures, the compiled kernels' helper process. threadpoolctl limits only the libraries loaded when it is
entered, so :func:`one_thread` loads scipy's BLAS first (numpy's is loaded with rotorcosim): one loaded later
would start with a thread per core. The exported FMUs cannot import rotorcosim; their slave
(fmus/slave_template.py) does the same by itself.
"""
from __future__ import annotations

import contextlib

from threadpoolctl import threadpool_limits


@contextlib.contextmanager
def one_thread():
    """Within: every BLAS and OpenMP pool loaded in the process runs one thread (restored on exit). Nests."""
    import scipy.linalg  # noqa: F401  (its BLAS loaded before the limit: module docstring)
    with threadpool_limits(limits=1):
        yield
