"""Observers: they watch a run and never change it.

- :mod:`.observers`: :class:`~.observers.Observer` (the protocol), :class:`~.observers.Recorder` (the time
  series, streamed to ``timeseries.h5`` or CSV), :class:`~.observers.Progress`, :class:`~.observers.SteadyWindows`
  (the last cycles of each thermo-mechanical interval, for a case's results);
- :mod:`.energy`: the energy exchanged through power bonds (force . velocity) and its residual;
- :mod:`.series`: reads a run's ``timeseries.h5`` back (lazily, dataset by dataset).
"""
