"""Observers: they watch a run and never change it.

- :mod:`.observer`: :class:`~.observer.Observer`, the protocol (the hooks a run calls);
- :mod:`.recorder`: :class:`~.recorder.Recorder`, the time series streamed to disk (and kept in memory on request),
  through its back-ends :mod:`.recorder_hdf5` (``timeseries.h5``) and :mod:`.recorder_csv`;
- :mod:`.progress`: :class:`~.progress.Progress`, the progress bar and its time-left estimate;
- :mod:`.steady_windows`: :class:`~.steady_windows.SteadyWindows`, the last cycles of each thermo-mechanical
  interval, for a case's results;
- :mod:`.energy`: the energy exchanged through power bonds (force . velocity) and its residual;
- :mod:`.series`: reads a run's ``timeseries.h5`` back (lazily, dataset by dataset);
- :mod:`.plausible`, :mod:`.validity`: the plausibility of a run's values and the validity of its models.
"""
