"""The coupling core: a system of components and connections, and the engine that steps it.

- :mod:`.system`: :class:`~.system.System` (components + connections, checked when built: sizes, units,
  causality, dangling inputs, each error naming the port) and :class:`~.system.Connection`;
- :mod:`.conversions`: unit and type conversions applied on a connection;
- :mod:`.links`: what an input sees of its output (copied, averaged, extrapolated, restarted; a hand-off window
  recorded): the state layout and the operations both execution paths run (plain functions, compiled as they are
  by the compiled path);
- :mod:`.algorithm`: the stepping algorithms (Gauss-Seidel, Jacobi), the links that carry a value from an
  output to an input (their state and operations: :mod:`.links`), :class:`~.algorithm.Engine` and
  :class:`~.algorithm.SimulationDiverged`.

Nothing here knows schedules, phases' meaning, observers or files; everything else in the master builds on it.
"""
