"""The same scenario gives the same numbers bit for bit, whatever the calling program imported first.

A program's OpenBLAS has one thread per core (importing rotorcosim changes no setting of the process);
multi-threaded BLAS sums in another order. master/core/threads.py limits the
pools to one thread around every run. Without it the API run below differed from the command line's by up to
1e-5 relative (measured on 2 cores)."""
import json
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

#: a 2 ms blade-loss run: the rotor's eigen-solves (components/rotor/mta.py) and a few hundred steps
ARGS = ["blade_loss_2850", "--duration", "0.002", "--no-figures", "--quiet"]

NUMPY_FIRST = """
import sys
import numpy, scipy.linalg
from threadpoolctl import threadpool_info, threadpool_limits
threadpool_limits(limits=4)   # left in force: the program's own choice
assert 'rotorcosim' not in sys.modules
assert all(p['num_threads'] > 1 for p in threadpool_info() if p['user_api'] == 'blas'), threadpool_info()
import rotorcosim
rotorcosim.simulate('blade_loss_2850', duration=0.002, out=sys.argv[1], figures=False)
assert all(p['num_threads'] == 4 for p in threadpool_info() if p['user_api'] == 'blas'), 'not restored'
"""


def _env():
    env = dict(os.environ)
    env.pop("OPENBLAS_NUM_THREADS", None)   # the programs below start with a BLAS pool per core, as a plain program
    env.pop("OMP_NUM_THREADS", None)
    return env


def _series(folder):
    with h5py.File(folder / "timeseries.h5", "r") as f:
        out = {}
        f.visititems(lambda name, d: out.__setitem__(name, d[()]) if isinstance(d, h5py.Dataset) else None)
    return out


def test_numpy_imported_first_with_threads_gives_the_command_lines_numbers(tmp_path):
    cli, api = tmp_path / "cli", tmp_path / "api"
    subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", *ARGS, "--out", str(cli)],
                   env=_env(), check=True, timeout=600, capture_output=True)
    done = subprocess.run([sys.executable, "-c", NUMPY_FIRST, str(api)], env=_env(), timeout=600,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    a, b = _series(cli), _series(api)
    assert sorted(a) == sorted(b) and len(a) > 2
    for name in a:
        assert a[name].shape == b[name].shape, name
        assert np.array_equal(a[name], b[name]), f"{name}: max difference {np.max(np.abs(a[name] - b[name]))}"


@pytest.mark.slow   # ~14 s of CPU time (measured): a local Dask cluster and two runs
def test_a_dask_worker_gives_the_command_lines_numbers(tmp_path):
    """The blade-loss case of a sweep, run in a Dask worker process, gives the command line's numbers bit for bit:
    the sweep runs the same model (scenario resolution, unbalance setting, engine) in another process. (Dask's
    nanny starts its workers with one BLAS thread of its own accord, so this does not test master/core/threads.py;
    the test above does.)"""
    from rotorcosim.master.cli.sweep import sweep

    cli = tmp_path / "cli"
    subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", *ARGS[:3], "--unbalance", "2850",
                    *ARGS[3:], "--out", str(cli)], env=_env(), check=True, timeout=600, capture_output=True)
    info = sweep([2850.0], tmp_path / "dask", "blade_loss", duration=0.002, workers=1)
    assert not info["errors"], info["errors"]
    assert info["executed_on"] != "serial"
    a, b = _series(cli), _series(tmp_path / "dask" / "F_2850")
    assert sorted(a) == sorted(b) and len(a) > 2
    for name in a:
        assert np.array_equal(a[name], b[name]), f"{name}: max difference {np.max(np.abs(a[name] - b[name]))}"


def test_importing_rotorcosim_sets_nothing_in_the_environment():
    """The thread limit is applied inside a run, not at import: a program that imports rotorcosim keeps its own
    environment (no OPENBLAS_NUM_THREADS) and its own BLAS threads."""
    code = ("import os, json; before = dict(os.environ); import rotorcosim, rotorcosim.master.api; "
            "print(json.dumps({k: v for k, v in os.environ.items() if before.get(k) != v}))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_env(), timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "{}", out.stdout


LOADED_INSIDE = """
import sys
import rotorcosim.master.core.threads as threads
assert 'numpy' not in sys.modules and 'scipy.linalg' not in sys.modules
from threadpoolctl import threadpool_info
with threads.one_thread():
    import scipy.linalg   # as a figure or an analysis that loads it first inside
    print([p['num_threads'] for p in threadpool_info() if p['user_api'] == 'blas'])
"""


def test_one_thread_holds_for_the_blas_a_caller_loads_inside_it():
    """threadpoolctl limits only the libraries loaded when it is entered: one_thread loads numpy's and scipy's BLAS
    first, so that a program that enters it before loading them (draw_figures called directly) gets one thread
    too. Needs a machine with more than one core, where a BLAS starts with more than one thread."""
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: every BLAS starts with one thread")
    out = subprocess.run([sys.executable, "-c", LOADED_INSIDE], capture_output=True, text=True, env=_env(),
                         timeout=120)
    assert out.returncode == 0, out.stderr
    counts = json.loads(out.stdout.strip())
    assert counts and all(n == 1 for n in counts), counts
