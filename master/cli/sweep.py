"""``rotorcosim sweep [SCENARIO] (--level LIST | --set comp.param=v1,v2,...) --out DIR [--scheduler ADDRESS]``.

A thin layer over :func:`rotorcosim.master.sweep.run_cases` (master/sweep/): this module makes the grid of cases
from the options and adds the case's tables.

A sweep is a grid of cases: the levels of the level option (``--level``, or the spelling the scenario's case
declares: values of the scenario's level parameter, master/case.py ``Level``) times every ``--set`` parameter's
values. Each case runs the scenario in a folder of its own, ``DIR/<prefix><level>`` for a level (the case's
``folder_prefix``), ``DIR/<comp.param>=<value>[_...]`` for a parameter grid.

Cases run on Dask: a local cluster (one single-threaded worker process per core) or, with ``--scheduler``, a
running cluster whose workers may be other machines. A worker runs its case in a temporary folder of its own and
sends the files back; the client writes them under ``--out`` (write-then-rename, so a case folder is whole or
absent). The sweep then writes ``DIR/sweep.json`` (cases, where they ran, wall times, errors), ``DIR/sweep.csv``
(one row per case: its parameters and its results) and, for a sweep of levels with at most one value of each
``--set`` parameter (one case a level), whatever tables the scenario's case writes for it (its ``SWEEP_TABLES``,
master/case.py), with their score in ``DIR/sweep.json`` under the case's ``SCORE_KEY``. What a sweep does under faults (a worker that dies, the
scheduler gone, Ctrl-C, a full disk, a second sweep into the folder) and ``--resume``: master/sweep/engine.py.
"""
from __future__ import annotations

import itertools
import re
import sys
from pathlib import Path
from typing import Any

from rotorcosim.master import case as cases_
from rotorcosim.master.api import SCHEDULES
from rotorcosim.master.run.outputs import check_dpi
from rotorcosim.master.scenario.overrides import parse_set
from rotorcosim.master.sweep import CONNECT_TIMEOUT_S, SWEEP_FILES, Case, run_cases

from rotorcosim.master.cli.options import SCHEDULE_HELP, add_dpi, add_out, add_scenario
from rotorcosim.master.cli.run import resolve


def add_arguments(p):
    """The options of ``rotorcosim sweep`` on the parser ``p``."""
    cases_.add_level_option(p, str, "LIST|NAME", "comma-separated values of the scenario's level parameter (SI), "
                                                "or the name of a set of levels its case declares (LEVELS)")
    p.add_argument("--set", action="append", default=[], metavar="COMP.PARAM=V1,V2,...",
                   help="a parameter and its values (repeatable: the sweep is the grid of all of them)")
    add_out(p, "output folder")
    p.add_argument("--scheduler", default=None,
                   help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default: a local cluster)")
    add_scenario(p, cases_.default_scenario(), note="the scenario every case runs (default: the base file of the "
                                                   "levels its case declares); the cases' results carry its name")
    p.add_argument("--duration", type=float, default=None, help="simulated duration [s] (cuts the timeline)")
    p.add_argument("--schedule", choices=sorted([*SCHEDULES, *cases_.schedule_aliases()]), default="scenario",
                   help=SCHEDULE_HELP)
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster size (default: number of cores; at most one per case)")
    p.add_argument("--serial", action="store_true", help="run the cases one after another, without Dask")
    p.add_argument("--quiet", action="store_true", help="no line per finished case")
    add_dpi(p)
    p.add_argument("--overwrite", action="store_true",
                   help="replace the results of a previous sweep in --out (which must otherwise be empty)")
    p.add_argument("--resume", action="store_true",
                   help="continue the sweep in --out (interrupted, or with failed cases): rerun only the cases "
                        "its sweep.json does not list as complete (same command otherwise)")
    p.add_argument("--force", action="store_true", help="run a sweep estimated above 24 h of wall time")


def parse_levels(text: str, named: dict | None = None, option: str = "--level", unit: str = "") -> list[float]:
    """``"1.5,3"`` -> ``[1.5, 3.0]``; a name of ``named`` (the scenario's case's ``LEVELS``) -> its levels.
    ``option``: the spelling given, ``unit`` the level's (for messages)."""
    if named and text.strip().lower() in named:
        return [float(f) for f in named[text.strip().lower()]]
    out = []
    for item in text.replace(" ", ",").split(","):
        if not item:
            continue
        try:
            f = float(item)
        except ValueError:
            names = f"one of the scenario's named sets ({', '.join(sorted(named))})" if named else \
                "a named set (the scenario's case declares none)"
            raise ValueError(f"{option}: {item!r} is neither a number nor {names}") from None
        if not (f >= 0 and f < float("inf")):
            raise ValueError(f"{option}: {item!r} must be a finite value >= 0{' ' + unit if unit else ''}")
        out.append(f)
    if not out:
        raise ValueError(f"{option}: no level given")
    if len(set(out)) != len(out):
        raise ValueError(f"{option}: a level is repeated")
    return out


def score_key_of(kind: str | None) -> str:
    """The key of sweep.json the score of the case ``kind``'s tables goes under (its ``SCORE_KEY``)."""
    return cases_.attribute(kind, "SCORE_KEY", "score") or "score"


def case_kind(scenario) -> str | None:
    """The case of ``scenario`` (its ``[results] kind``), or None."""
    return resolve(scenario).extra.get("results", {}).get("kind")


def parse_grid(items: list[str]) -> dict[str, list[Any]]:
    """``["comp.param=v1,v2", ...]`` -> ``{"comp.param": [v1, v2], ...}`` (order kept); each item read by the
    one ``--set`` parser, :func:`rotorcosim.master.scenario.overrides.parse_set`."""
    grid: dict[str, list[Any]] = {}
    for item in items:
        where = f"--set {item!r}"
        ref, vals = parse_set(item, values=True)
        if ref in grid:
            raise ValueError(f"{where}: {ref} is given twice")
        if len(set(map(repr, vals))) != len(vals):
            raise ValueError(f"{where}: a value is repeated")
        grid[ref] = vals
    return grid


#: the longest case folder name (file systems take 255 bytes; the sweep adds ".part" while it writes)
NAME_MAX = 200


def _fmt(v: Any) -> str:
    """A value as it stands in a case's folder name: a file path by its file name (``--set
    rotor.model_file=/abs/engine.toml`` -> ``engine.toml``), control characters and other slashes (inside a list
    value) as ``_``."""
    text = f"{v:g}" if isinstance(v, float) else str(v).lower() if isinstance(v, bool) else str(v)
    if isinstance(v, str) and ("/" in text or "\\" in text):
        text = re.split(r"[/\\]", text.rstrip("/\\"))[-1] or "root"
    return re.sub(r"[\x00-\x1f\x7f/\\]", "_", text)


def one_case_a_level(levels, grid: dict[str, list[Any]]) -> bool:
    """Whether the sweep has levels and one case at each (one value of every ``--set`` parameter): the sweeps
    whose case writes its tables of the levels (``SWEEP_TABLES``)."""
    return bool(levels) and all(len(v) == 1 for v in grid.values())


def cases_of(levels: list[float] | None, grid: dict[str, list[Any]], scenario=None, duration=None,
             schedule=None, dpi=None, level=None) -> list[Case]:
    """The grid of cases of ``scenario`` (None: :func:`rotorcosim.master.case.default_scenario`): its levels
    (outer; folders named with its case's ``folder_prefix``) times the ``--set`` parameters' values. Each
    case's folder name says its values (:func:`_fmt`); two cases whose names would be the same (two files of one
    name in different folders) are an error naming both values."""
    scenario = cases_.default_scenario() if scenario is None else scenario
    level = level or cases_.scenario_level(resolve(scenario))[0]
    if not levels and not grid:
        raise ValueError(f"nothing to sweep: give {level.option} and/or --set")
    out, seen = [], {}
    refs = list(grid)
    for f in levels or [None]:
        for combo in itertools.product(*(grid[r] for r in refs)):
            parts = ([f"{level.folder_prefix}{f:g}"] if f is not None else []) + [f"{r}={_fmt(v)}" for r, v in zip(refs, combo)]
            name = "_".join(parts)
            if len(name.encode()) > NAME_MAX:
                raise ValueError(f"case name {name[:60]!r}... is {len(name.encode())} bytes, longer than a folder "
                                 f"name may be ({NAME_MAX}): use shorter values")
            if name.startswith("."):
                raise ValueError(f"case name {name!r} is not a usable folder name (a hidden one): use plainer values")
            settings = dict(zip(refs, combo))
            if name in seen:
                raise ValueError(f"two cases would share the folder {name!r}: {seen[name]} and {settings} (give "
                                 f"the files different names)")
            seen[name] = settings
            out.append(Case(name, scenario, settings, f, duration, schedule, dpi))
    return out


def sweep(levels=None, out: Path = Path("sweep"), scenario=None, scheduler=None, schedule=None,
          duration=None, workers=None, serial=False, grid: dict[str, list[Any]] | None = None,
          progress=None, connect_timeout: float = CONNECT_TIMEOUT_S, overwrite: bool = False,
          resume: bool = False, dpi=None, force: bool = False, say=None) -> dict:
    """Run the grid of ``levels`` (values of the scenario's level parameter, SI) x ``grid``
    (``{"comp.param": [values]}``) into ``out`` (:func:`rotorcosim.master.sweep.run_cases`, which says what
    happens under faults; ``resume`` reruns only the cases a previous sweep into ``out`` did not complete);
    ``dpi``: the cases' figures' resolution (None: the default); ``force``: run a sweep estimated above 24 h;
    ``say``: a function of one line, given the sweep's estimate before the first case.

    ``progress(done, total, case, result)`` is called as each case finishes. Returns the contents of
    ``sweep.json``."""
    grid = dict(grid or {})
    scenario = cases_.default_scenario() if scenario is None else scenario
    sc = resolve(scenario)
    kind = sc.extra.get("results", {}).get("kind")
    level = cases_.scenario_level(sc)[0]
    cases = cases_of(list(levels) if levels else None, grid, scenario, duration, schedule, check_dpi(dpi), level)
    tables = cases_.attribute(kind, "SWEEP_TABLES")
    score_key = score_key_of(kind)

    def finish(folder: Path, summaries: dict) -> dict:
        score = None
        if tables is not None and one_case_a_level(levels, grid):
            score = tables(folder, {c.level: summaries[c.name] for c in cases})
        return {score_key: score}

    info = {level.sweep_key: list(levels or []), "parameters": {r: vs for r, vs in grid.items()}}
    done = run_cases(cases, out, scheduler=scheduler, workers=workers, serial=serial, progress=progress,
                     overwrite=overwrite, resume=resume, info=info, finish=finish,
                     extra_files=cases_.attribute(kind, "SWEEP_FILES", ()), connect_timeout=connect_timeout,
                     force=force, say=say)
    return done.state


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status (1 when a case failed)."""
    sc = resolve(args.scenario)
    kind_of_case = sc.extra.get("results", {}).get("kind")
    level = cases_.scenario_level(sc)[0]
    levels = parse_levels(args.level, cases_.attribute(kind_of_case, "LEVELS", {}), args.level_option or level.option,
                          level.unit) if args.level else None
    grid = parse_grid(args.set)
    if levels:  # the level's own checks in the spelling given (a --set of the level parameter too is an error)
        cases_.apply_level(sc, levels[0], list(grid), args.level_option or level.option)
    kind = SCHEDULES[cases_.schedule_aliases().get(args.schedule, args.schedule)]

    def progress(done, total, case, res):
        err = res["summary"].get("error")
        wall = res["summary"].get("wall_time_s")
        state = f"failed: {err}" if err else (f"done in {wall:.3g} s" if wall else "done")
        retry = res.get("retry")
        if retry:
            state += (f" (attempt {retry['attempt']}, on {retry['worker']}: its worker "
                      f"{', '.join(retry['died_on'])} died)")
        print(f"[{done}/{total}] {case.name}: {state}", file=sys.stderr, flush=True)

    info = sweep(levels, Path(args.out), args.scenario, args.scheduler, kind, args.duration, args.workers,
                 args.serial, grid, None if args.quiet else progress, overwrite=args.overwrite, resume=args.resume,
                 dpi=args.dpi, force=args.force, say=lambda line: print(line, file=sys.stderr, flush=True))
    # the files at the top of the folder are this sweep's (a previous sweep's were refused or cleared)
    tables = sorted(p.name for p in Path(args.out).iterdir() if p.is_file() and p.name not in SWEEP_FILES[:2])
    print(f"{len(info['cases'])} cases in {info['wall_time_s']:.3g} s ({info['executed_on']});"
          f"{''.join(f' {t},' for t in tables)} sweep.csv and sweep.json written in {args.out}")
    score = info.get(score_key_of(kind_of_case))
    line = cases_.attribute(kind_of_case, "SWEEP_SCORE")
    if score and line is not None:
        print(line(score, args.out))
    for name, r in info.get("retries", {}).items():
        print(f"  case {name} was run again on {r['worker']} after its worker {', '.join(r['died_on'])} died: "
              f"{r['result']}", file=sys.stderr)
    for name, e in info["errors"].items():
        print(f"  case {name} failed: {e}", file=sys.stderr)
    return 1 if info["errors"] else 0
