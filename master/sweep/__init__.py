"""Sweeps: many cases of a scenario run on Dask (or one after another) into one folder.

- :mod:`.case`: :class:`Case` (a scenario, its level, parameter overrides, a duration, a schedule) and
  :func:`run_case`, which runs one where it is sent and returns its files;
- :mod:`.folder`: the sweep's folder: its lock, previous results (refused, replaced, resumed), each case's
  folder written whole, ``sweep.json``;
- :mod:`.engine`: :func:`run_cases`, the cases on a Dask client (local or ``scheduler=ADDRESS``) and what it
  does under faults (a worker that dies, the scheduler gone, Ctrl-C, a full disk);
- :mod:`.retry`: :func:`~.retry.run_retried`, tasks on Dask whose worker may die, each run again
  :data:`~.retry.RETRIES` times at most (the sweeps' and the studies' one retry mechanism).

``rotorcosim sweep`` (master/cli/sweep.py) is a thin layer over :func:`run_cases`::

    from rotorcosim.master.sweep import Case, run_cases
    cases = [Case("stiff", "toy_thermomechanical", {"node.C": 10.0}, duration=0.05),
             Case("soft", "toy_thermomechanical", {"node.C": 20.0}, duration=0.05)]
    done = run_cases(cases, "out", scheduler="tcp://10.0.0.5:8786")   # default: a local cluster
    done.summaries["soft"], done.errors
"""
from rotorcosim.master.sweep.case import Case, run_case
from rotorcosim.master.sweep.engine import (CONNECT_TIMEOUT_S, SchedulerLost, SweepError, SweepInterrupted, SweepRun,
                                            WorkerDied, run_cases)
from rotorcosim.master.sweep.folder import SWEEP_FILES, DiskFullError, SweepFolder, named_os_error
from rotorcosim.master.sweep.retry import RETRIES

__all__ = ["Case", "run_case", "run_cases", "SweepRun", "SweepError", "SweepInterrupted", "SchedulerLost", "WorkerDied",
           "DiskFullError", "SweepFolder", "named_os_error", "SWEEP_FILES", "CONNECT_TIMEOUT_S", "RETRIES"]
