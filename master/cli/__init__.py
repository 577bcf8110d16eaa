"""The ``rotorcosim`` command line: a thin layer over the Python API (:mod:`rotorcosim.master.api`).

:mod:`.program` holds the parser, the command table and :func:`main`; each command is a module with
``add_arguments(parser)`` and ``run(args) -> int`` (:mod:`.run`, :mod:`.sweep`, :mod:`.scenarios`,
:mod:`.export_fmus`, :mod:`.export_ssp`; a case adds its own, e.g. ``compare``). ``python -m rotorcosim.master.cli``
is the ``rotorcosim`` program::

    from rotorcosim.master.cli import main
    main(["run", "--duration", "0.05", "--no-figures", "--out", "out"])   # returns the exit status
"""
from rotorcosim.master.cli.program import main

__all__ = ["main"]
