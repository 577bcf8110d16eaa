"""Run infrastructure: what a run on disk needs around the simulation.

- :mod:`.options`: a run's options, checked once (:class:`~.options.RunOptions`);
- :mod:`.session`: one run and what surrounds it (:class:`~.session.RunSession`): folder, checkpoints, watchdog,
  provenance, recorder;
- :mod:`.summary`: summary.json's dict, made from the run's report;
- :mod:`.rundir`: the output folder (its lock, ``--overwrite`` / ``--resume`` rules, which files are a run's);
- :mod:`.outputs`: files written whole or not at all (``summary.json``);
- :mod:`.checkpoint`: checkpoints and ``--resume``;
- :mod:`.watchdog`: a run that stops on a signal or a stall keeps what it recorded;
- :mod:`.profiling`: ``--profile``;
- :mod:`.figure_pool`, :mod:`.figure_worker`: figures drawn in worker processes from the time series file.
"""
