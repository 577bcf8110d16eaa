"""Builders shared by the tests (not tests themselves), imported as ``tests.helpers.<module>``.

- ``fmus``: FMU builds and whole-trajectory capture for the FMI-boundary tests (tests/fmus, tests/reliability);
- ``systems``: the two-mass system with its exact solution for the master's tests;
- ``faulty``: a thermal node that fails on demand (kills its process, raises, NaN, sleeps) and a real Dask
  cluster of separate processes, for the sweep fault tests (tests/reliability).
"""
