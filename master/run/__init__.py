"""Run infrastructure: what a run on disk needs around the simulation.

- :mod:`.rundir`: the output folder (its lock, ``--overwrite`` / ``--resume`` rules, which files are a run's);
- :mod:`.outputs`: files written whole or not at all (``summary.json``);
- :mod:`.checkpoint`: checkpoints and ``--resume``;
- :mod:`.watchdog`: a run that stops on a signal or a stall keeps what it recorded;
- :mod:`.threads`: one BLAS thread during a run (the same numbers whatever was imported first);
- :mod:`.profiling`: ``--profile``;
- :mod:`.figure_pool`, :mod:`.figure_worker`: figures drawn in worker processes from the time series file.
"""
