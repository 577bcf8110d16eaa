"""How a case plugs into the master: a study's results, figures and commands, found by name.

A scenario names its case in ``[results] kind``. The name resolves, in this order, to

1. ``"package.module:object"``: that object;
2. an entry point of the group ``rotorcosim.cases`` with that name (a case installed by another package);
3. the package ``rotorcosim.cases.<kind>`` (the cases shipped here, e.g. ``blade_loss``).

A case is a module or object with any of these attributes:

- ``RESULTS``: the dotted name of the module that turns a run into the scenario's results, offering
  ``observers(sc, cycle)`` (``cycle``: the scenario's cycle source, master/core/cycle.py), ``check(sc, sim)``,
  ``extract(sc, sim, observers, report) -> dict``, ``figures(sc, series, out, pool=None, dpi=None) -> list[str]``
  (``dpi``: the figures' resolution, dots per inch; None: the default) and
  optionally ``FIGURES_MODULE``;
- ``LEVELS``: named sets of levels of the scenario's level parameter (``[results] unbalance_parameter``) for
  ``rotorcosim sweep --unbalance NAME`` (e.g. ``{"paper": (712.0, ...)}``);
- ``SWEEP_TABLES``: ``"module:function"``, ``function(out, by_level) -> score | None``, called after a sweep with
  one case per level (``by_level``: level -> summary) to write the case's own tables;
- ``SWEEP_FILES``: the names (glob patterns) of the files ``SWEEP_TABLES`` writes, which ``sweep --overwrite``
  may clear;
- ``SWEEP_SCORE``: ``"module:function"``, ``function(score, out) -> str``, the line ``rotorcosim sweep`` prints
  for a score of ``SWEEP_TABLES``;
- ``COMMANDS``: ``{"command-name": ("dotted.module", "one line of help")}``, added to the ``rotorcosim`` program
  (each module offers ``add_arguments(parser)`` and ``run(args) -> int``, as the master's own commands);
- ``COMPARE``: ``"module:function"``, ``function(args, sc) -> int``: what ``rotorcosim compare SCENARIO`` does
  for a scenario of this case (``args``: the command's parsed options, ``sc``: the scenario with its ``--set`` /
  ``--swap`` / ``--unbalance`` applied); without it ``compare`` is the blade-loss case's Table 6.

The master names no case: it asks this module.
"""
from __future__ import annotations

import importlib
import pkgutil
from importlib import metadata
from types import ModuleType
from typing import Any

GROUP = "rotorcosim.cases"
#: where the cases shipped with rotorcosim live (a namespace, not an import of them)
SHIPPED = "rotorcosim.cases"


class CaseError(ValueError):
    """A case name that resolves to nothing usable (one line naming the name and why)."""


def find(kind: str) -> Any:
    """The case named ``kind`` (see the module's docstring for the order), imported."""
    if not isinstance(kind, str) or not kind.strip():
        raise CaseError(f"case {kind!r}: give a name, or 'module:object'")
    if ":" in kind:
        module, _, attr = kind.partition(":")
        try:
            return getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError) as exc:
            raise CaseError(f"case {kind!r}: cannot be imported ({exc})") from None
    for ep in metadata.entry_points(group=GROUP):
        if ep.name == kind:
            return ep.load()
    if not kind.isidentifier():
        raise CaseError(f"case {kind!r}: not a case name (a Python identifier, or 'module:object')")
    try:
        return importlib.import_module(f"{SHIPPED}.{kind}")
    except ModuleNotFoundError as exc:
        raise CaseError(f"case {kind!r}: no such case ({exc})") from None


def results_of(kind: str) -> ModuleType:
    """The result extraction of the case ``kind`` (its ``RESULTS`` module)."""
    case = find(kind)
    name = getattr(case, "RESULTS", None)
    if name is None:
        raise CaseError(f"case {kind!r} has no result extraction (RESULTS)")
    try:
        return importlib.import_module(name) if isinstance(name, str) else name
    except ModuleNotFoundError as exc:
        raise CaseError(f"case {kind!r}: its result extraction {name!r} cannot be imported ({exc})") from None


def attribute(kind: str | None, name: str, default: Any = None) -> Any:
    """The attribute ``name`` of the case ``kind`` (None: no case, the default); a ``"module:object"`` string
    there is imported."""
    if not kind:
        return default
    value = getattr(find(kind), name, default)
    if isinstance(value, str) and ":" in value:
        module, _, attr = value.partition(":")
        value = getattr(importlib.import_module(module), attr)
    return value


def all_cases() -> dict[str, Any]:
    """Every case that can be found without a scenario: the shipped ones and the installed entry points."""
    out: dict[str, Any] = {}
    try:
        shipped = importlib.import_module(SHIPPED)
    except ModuleNotFoundError:
        shipped = None
    if shipped is not None:
        for info in pkgutil.iter_modules(shipped.__path__):
            if info.ispkg:
                out[info.name] = importlib.import_module(f"{SHIPPED}.{info.name}")
    for ep in metadata.entry_points(group=GROUP):
        out.setdefault(ep.name, ep)
    return out


def commands() -> dict[str, tuple[str, str]]:
    """The commands every findable case adds to the ``rotorcosim`` program (entry points are loaded only for
    their ``COMMANDS``)."""
    out: dict[str, tuple[str, str]] = {}
    for name, case in all_cases().items():
        if isinstance(case, metadata.EntryPoint):
            case = case.load()
        out.update(getattr(case, "COMMANDS", {}) or {})
    return out
