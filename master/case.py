"""How a case plugs into the master: a study's results, figures and commands, found by name.

A scenario names its case in ``[results] kind``. The name resolves, in this order, to

1. ``"package.module:object"``: that object;
2. an entry point of the group ``rotorcosim.cases`` with that name (a case installed by another package);
3. the package ``rotorcosim.cases.<kind>`` (the cases shipped with rotorcosim).

A case is a module or object with any of these attributes:

- ``RESULTS``: the dotted name of the module that turns a run into the scenario's results, offering
  ``observers(sc, cycle)`` (``cycle``: the scenario's cycle source, master/core/cycle.py), ``check(sc, sim)``,
  ``extract(sc, sim, observers, report) -> dict``, ``figures(sc, series, out, pool=None, dpi=None) -> list[str]``
  (``dpi``: the figures' resolution, dots per inch; None: the default) and
  optionally ``FIGURES_MODULE``;
- ``LEVEL``: the level the case sweeps, a dict of :class:`Level`'s fields: the ``[results]`` key of its scenarios
  that names the component parameter holding it, its name, its command-line spelling (for ``run``, ``sweep``),
  unit, label, and the keys its summaries and sweeps report it under;
- ``LEVELS``: named sets of levels of the scenario's level parameter for ``rotorcosim sweep <spelling> NAME``
  (e.g. ``{"name": (1.0, 2.0, ...)}``);
- ``DEFAULT_SCENARIO``: the scenario ``sweep`` and ``export-ssp`` start from when none is named;
- ``SCHEDULE_ALIASES``: names of ``--schedule`` / ``simulate(schedule=...)`` the case adds (alias -> one of
  ``scenario``, ``auto``, ``monolithic``);
- ``RESULTS_KEYS``: ``{"key": checker}``, the case's own keys of ``[results]`` (checked when a scenario of the
  case is loaded; a checker is one of master/scenario/checkers.py's: None or the error);
- ``SCORE_KEY``: the key of ``sweep.json`` the score of ``SWEEP_TABLES`` is written under;
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
  ``--swap`` / level applied).

The master names no case: it asks this module.
"""
from __future__ import annotations

import argparse
import functools
import importlib
import pkgutil
from dataclasses import dataclass
from importlib import metadata
from types import ModuleType
from typing import Any

from rotorcosim import scenarios
from rotorcosim.master.scenario.checkers import did_you_mean
from rotorcosim.master.scenario.tables import TABLES
from rotorcosim.components.contract import ContractError
from rotorcosim.master.scenario.overrides import declared_parameters, set_level

GROUP = "rotorcosim.cases"
#: where the cases shipped with rotorcosim live (a namespace, not an import of them)
SHIPPED = "rotorcosim.cases"


@functools.cache
def installed() -> dict[str, metadata.EntryPoint]:
    """The entry points of the group ``rotorcosim.cases``, name -> entry point, read once per process: reading
    every installed distribution's metadata takes ~20 ms, and a run asks for its case several times."""
    out: dict[str, metadata.EntryPoint] = {}
    for ep in metadata.entry_points(group=GROUP):
        out.setdefault(ep.name, ep)   # the first of a name, as a scan would find it
    return out


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
    ep = installed().get(kind)
    if ep is not None:
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
    for name, ep in installed().items():
        out.setdefault(name, ep)
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


# -- the level a case sweeps -------------------------------------------------------------------------------
#: the generic ``[results]`` key naming a scenario's level parameter (any scenario, with or without a case)
LEVEL_KEY = "level_parameter"


@dataclass(frozen=True)
class Level:
    """The level of a study (the quantity ``run``/``sweep`` set by one option): ``results_key``, the ``[results]``
    key naming the component parameter that holds it; ``name`` (its key in a scenario's edits); ``option``, its
    command-line spelling; ``unit`` (SI) and ``label`` (what it is, for messages and help); ``summary_key``
    (where a run's summary reports it), ``sweep_key`` (sweep.json's list of levels), ``folder_prefix`` (a
    sweep's case folder per level, ``<prefix><value>``)."""

    results_key: str = LEVEL_KEY
    name: str = "level"
    option: str = "--level"
    unit: str = ""
    label: str = "level"
    summary_key: str = "level"
    sweep_key: str = "levels"
    folder_prefix: str = "level_"


#: a scenario without a case's level: the generic one
GENERIC = Level()


def _level(case_obj) -> Level | None:
    spec = getattr(case_obj, "LEVEL", None)
    return Level(**spec) if isinstance(spec, dict) else spec


def level_of(kind: str | None) -> Level:
    """The level of the case ``kind`` (:data:`GENERIC` without a case or without a declared level)."""
    return (_level(find(kind)) if kind else None) or GENERIC


def scenario_level(sc) -> tuple[Level, str | None]:
    """(the level of scenario ``sc``, the ``comp.param`` holding it or None): its case's ``[results]`` key, or
    the generic ``level_parameter``."""
    res = sc.extra.get("results", {})
    level = level_of(res.get("kind"))
    return level, res.get(level.results_key) or res.get(LEVEL_KEY)


def apply_level(sc, value: float, settings=(), option: str | None = None) -> None:
    """Set the level parameter of ``sc`` (in place) to ``value`` (SI), recorded in its edits; ``settings``: the
    ``comp.param`` names the same command sets with ``--set`` (naming the level parameter there too is an error);
    ``option``: the spelling the user gave (for messages; default the level's own)."""
    level, ref = scenario_level(sc)
    set_level(sc, value, ref, name=level.name, option=option or level.option, unit=level.unit, label=level.label,
              key=level.results_key, settings=settings)


def level_options() -> dict[str, Level]:
    """The command-line spellings of the level that the findable cases declare, and the generic ``--level``."""
    out = {GENERIC.option: GENERIC}
    for case_obj in _loaded_cases():
        level = _level(case_obj)
        if level is not None:
            out.setdefault(level.option, level)
    return out


class _LevelAction(argparse.Action):
    """Stores the value as ``level`` and the spelling used as ``level_option`` (messages name what was typed)."""

    def __call__(self, parser, namespace, values, option_string=None):
        namespace.level = values
        namespace.level_option = option_string


def add_level_option(parser, type_=float, metavar="VALUE", help_text: str | None = None) -> None:
    """The level option of a command, in every spelling the cases declare (:func:`level_options`)."""
    opts = level_options()
    said = "; ".join(f"{o}: {lv.label} [{lv.unit}]" if lv.unit else f"{o}: {lv.label}"
                     for o, lv in sorted(opts.items()) if lv is not GENERIC)
    parser.add_argument(*sorted(opts), action=_LevelAction, dest="level", type=type_, default=None,
                        metavar=metavar,
                        help=(help_text or "the value of the scenario's level parameter (SI)")
                        + (f" ({said})" if said else ""))
    parser.set_defaults(level_option=None)


def default_scenario() -> str:
    """The scenario a command starts from when none is named and it needs a case's base file (``sweep``,
    ``export-ssp``): the ``DEFAULT_SCENARIO`` a findable case declares, else the shipped default."""
    for case_obj in _loaded_cases():
        name = getattr(case_obj, "DEFAULT_SCENARIO", None)
        if name:
            return name
    return scenarios.DEFAULT


def schedule_aliases() -> dict[str, str]:
    """Every ``--schedule`` alias the findable cases declare (alias -> schedule name)."""
    out: dict[str, str] = {}
    for case_obj in _loaded_cases():
        out.update(getattr(case_obj, "SCHEDULE_ALIASES", {}) or {})
    return out


def check_results(sc) -> None:
    """The ``[results]`` keys of ``sc`` that the schema left to its case: each one the case declares
    (``RESULTS_KEYS``), of the declared form; and the level's ``comp.param`` (the case's key, or any scenario's
    ``level_parameter``) a parameter of a component of ``sc``. A one-line ValueError naming the key otherwise."""
    res = sc.extra.get("results", {})
    kind = res.get("kind")
    where = f"{sc.source or sc.name}: [results]"
    if kind:
        own = dict(getattr(find(kind), "RESULTS_KEYS", {}) or {})
        for key, value in res.items():
            if key in TABLES["results"]:
                continue
            if key not in own:
                known = [*TABLES["results"], *own]
                raise ValueError(f"{where} {key}: unknown key{did_you_mean(key, known)} (case {kind!r}); known: "
                                 f"{', '.join(known)}")
            err = own[key](value)
            if err:
                raise ValueError(f"{where} {key}: {err}")
    level, ref = scenario_level(sc)
    if isinstance(ref, str):   # the case's own key, or the generic level_parameter of any scenario
        key = level.results_key if res.get(level.results_key) else LEVEL_KEY
        _check_level_parameter(sc, f"{where} {key}", ref)


def _check_level_parameter(sc, where: str, ref: str) -> None:
    """The level's ``comp.param`` must be a parameter the component has: a misspelt one was accepted and the
    run reported no level (its summary's level key null), the level's command-line option then refused by the
    component."""
    comp, _, param = ref.partition(".")
    if comp not in sc.components:
        raise ValueError(f"{where}: {ref!r}: no component {comp!r}")
    try:
        known = declared_parameters(sc.components[comp])
    except ContractError:   # an implementation that cannot be looked up: the build names it
        return
    if known is not None and param not in known:
        raise ValueError(f"{where}: {ref!r}: component {comp!r} has no parameter {param!r}"
                         f"{did_you_mean(param, list(known))}")


def _loaded_cases():
    for case_obj in all_cases().values():
        yield case_obj.load() if isinstance(case_obj, metadata.EntryPoint) else case_obj
