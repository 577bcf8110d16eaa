"""Staggered against monolithic for any scenario: ``compare_schemes`` and the relative errors it is judged by.

- :mod:`.schemes`: :func:`compare_schemes` runs a scenario under a staggered and a monolithic schedule into one
  folder, times both, writes the table a case makes of them; with the folder rules of every command (a lock,
  ``--overwrite``, ``--resume``, Ctrl-C keeps the complete runs, a reused monolithic run);
- :mod:`.errors`: :func:`rel_error_pct`, :func:`pair` (one quantity: staggered, monolithic, relative error) and
  :func:`within` (a group of quantities against a tolerance).

The shipped cases build their ``rotorcosim compare`` on it, each with its own schedules and table.
"""
from rotorcosim.master.compare.errors import pair, rel_error_pct, within
from rotorcosim.master.compare.schemes import (KINDS, SAME, LevelValue, compare_schemes, draw, edits_of, kept_run,
                                               load_average, quantum, reused_monolithic)

__all__ = ["compare_schemes", "LevelValue", "KINDS", "SAME", "pair", "rel_error_pct", "within", "kept_run",
           "reused_monolithic", "draw", "load_average", "quantum", "edits_of"]
