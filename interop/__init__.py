"""Rotors exchanged with ROSS, the open rotordynamics library (``pip install "rotorcosim[ross]"``).

- :func:`from_ross`: a live ``ross.Rotor`` (or ``CoAxialRotor``), or a TOML file written by ROSS's
  ``Rotor.save``, to an engine description of rotorcosim's engine format (docs/reference/engine-format.md).
  Reading a file needs no ROSS installed (:mod:`.ross_toml`).
- :func:`to_ross`: an engine file (or description) to a ``ross.Rotor`` of its linear rotor, the co-simulated
  bearings linearised as ``rotorcosim critical-speeds`` does, for ROSS's Campbell, mode-shape and UCS plots.
- :func:`write_engine`: an engine description to a TOML file.

Example::

    from rotorcosim.interop import from_ross, to_ross, write_engine
    engine = from_ross("rotor_example.toml")       # or from_ross(ross.rotor_example())
    write_engine(engine, "engine.toml")
    rotor = to_ross("engine.toml")                 # a ross.Rotor; rotor.run_campbell(...).plot()
"""
from __future__ import annotations


def from_ross(rotor, **kw) -> dict:
    """See :func:`rotorcosim.interop.ross_import.from_ross`."""
    from .ross_import import from_ross as _f

    return _f(rotor, **kw)


def to_ross(engine, **kw):
    """See :func:`rotorcosim.interop.ross_export.to_ross`."""
    from .ross_export import to_ross as _f

    return _f(engine, **kw)


def write_engine(engine: dict, path) -> None:
    """See :func:`rotorcosim.interop.engine_toml.write`."""
    from .engine_toml import write

    write(engine, path)
