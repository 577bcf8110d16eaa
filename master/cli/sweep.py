"""``rotorcosim sweep [SCENARIO] (--unbalance LIST | --set comp.param=v1,v2,...) --out DIR [--scheduler ADDRESS]``.

A sweep is a grid of cases: the levels of ``--unbalance`` (values of the scenario's level parameter, its
``[results] unbalance_parameter``) times every ``--set`` parameter's values. Each case runs the scenario in a
folder of its own, ``DIR/F_<level>`` for a level, ``DIR/<comp.param>=<value>[_...]`` for a parameter grid.

Cases run on Dask: a local cluster (one single-threaded worker process per core) or, with ``--scheduler``, a
running cluster whose workers may be other machines. A worker runs its case in a temporary folder of its own and
sends the files back; the client writes them under ``--out`` (write-then-rename, so a case folder is whole or
absent). The sweep then writes ``DIR/sweep.json`` (cases, where they ran, wall times, errors), ``DIR/sweep.csv``
(one row per case: its parameters and its results) and, for a sweep of levels with at most one value of each
``--set`` parameter (one case a level), whatever tables the scenario's case writes for it (its ``SWEEP_TABLES``,
master/case.py; the blade-loss case: ``table5.csv`` / ``table5.md`` and its comparison with the paper), with
their score in ``DIR/sweep.json`` (``paper_score``).
"""
from __future__ import annotations

import csv
import fnmatch
import itertools
import os
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rotorcosim.master import case as cases_
from rotorcosim.master.api import SCHEDULE_ALIASES, SCHEDULES, check_run
from rotorcosim.master.run.outputs import check_dpi, write_json
from rotorcosim.master.scenario.overrides import apply_set, parse_set
from rotorcosim.master.run.rundir import OutputFolderError, check_folder, ensure_folder, is_run_file

from rotorcosim.master.cli.options import SCHEDULE_HELP, add_dpi, add_out, add_scenario
from rotorcosim.master.cli.run import apply_unbalance, execute, resolve

#: how long the client waits for a scheduler given by --scheduler before saying it cannot reach it [s]
CONNECT_TIMEOUT_S = 20.0


def add_arguments(p):
    """The options of ``rotorcosim sweep`` on the parser ``p``."""
    p.add_argument("--unbalance", default=None, metavar="LIST|NAME",
                   help="comma-separated values of the scenario's level parameter ([results] unbalance_parameter, "
                        "SI), or the name of a set of levels its case declares (e.g. 'paper')")
    p.add_argument("--set", action="append", default=[], metavar="COMP.PARAM=V1,V2,...",
                   help="a parameter and its values (repeatable: the sweep is the grid of all of them)")
    add_out(p, "output folder")
    p.add_argument("--scheduler", default=None,
                   help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default: a local cluster)")
    add_scenario(p, "blade_loss", note="the scenario every case runs; the levels' base file, F_u = 2850 N as in "
                                       "blade_loss_2850 that run uses; the cases' results carry its name")
    p.add_argument("--duration", type=float, default=None, help="simulated duration [s] (cuts the timeline)")
    p.add_argument("--schedule", choices=sorted([*SCHEDULES, *SCHEDULE_ALIASES]), default="scenario",
                   help=SCHEDULE_HELP)
    p.add_argument("--workers", type=int, default=None,
                   help="local cluster size (default: number of cores; at most one per case)")
    p.add_argument("--serial", action="store_true", help="run the cases one after another, without Dask")
    p.add_argument("--quiet", action="store_true", help="no line per finished case")
    add_dpi(p)
    p.add_argument("--overwrite", action="store_true",
                   help="replace the results of a previous sweep in --out (which must otherwise be empty)")


def parse_levels(text: str, named: dict | None = None) -> list[float]:
    """``"712,1425"`` -> ``[712.0, 1425.0]``; a name of ``named`` (the scenario's case's ``LEVELS``, e.g.
    ``"paper"``) -> its levels."""
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
            raise ValueError(f"--unbalance: {item!r} is neither a number nor {names}") from None
        if not (f >= 0 and f < float("inf")):
            raise ValueError(f"--unbalance: {item!r} must be a finite force >= 0 N")
        out.append(f)
    if not out:
        raise ValueError("--unbalance: no level given")
    if len(set(out)) != len(out):
        raise ValueError("--unbalance: a level is repeated")
    return out


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


@dataclass
class Case:
    """One run of the sweep: its folder name and the parameters it sets (``comp.param`` -> value)."""
    name: str
    settings: dict[str, Any] = field(default_factory=dict)
    unbalance_N: float | None = None


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


def cases_of(levels: list[float] | None, grid: dict[str, list[Any]]) -> list[Case]:
    """The grid of cases: unbalance levels (outer) times the ``--set`` parameters' values. Each case's folder
    name says its values (:func:`_fmt`); two cases whose names would be the same (two files of one name in
    different folders) are an error naming both values."""
    if not levels and not grid:
        raise ValueError("nothing to sweep: give --unbalance and/or --set")
    out, seen = [], {}
    refs = list(grid)
    for f in levels or [None]:
        for combo in itertools.product(*(grid[r] for r in refs)):
            parts = ([f"F_{f:g}"] if f is not None else []) + [f"{r}={_fmt(v)}" for r, v in zip(refs, combo)]
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
            out.append(Case(name, settings, f))
    return out


def _apply(sc, case: Case):
    """The scenario of ``case``: ``sc`` with its unbalance and its ``--set`` values (checked as ``run --set``'s:
    the component, the parameter, the value's kind)."""
    if case.unbalance_N is not None:
        apply_unbalance(sc, case.unbalance_N, case.settings)
    if case.settings:
        sc = apply_set(sc, case.settings, origin="--set")
        sc.name = f"{sc.name}_{case.name}"
    return sc


def run_case(scenario: str, case: Case, schedule: str | None, duration: float | None, dpi: float | None = None) -> dict:
    """One case, run where it is called (a Dask worker or this process), in a temporary folder of its own, its
    figures at ``dpi`` (None: the default).

    Returns ``{"summary": ..., "files": {relative path: bytes}, "host": ...}``: the caller writes the files
    where it wants them, so a worker needs no access to the client's folders."""
    import socket

    work = Path(tempfile.mkdtemp(prefix="rotorcosim-case-"))
    try:
        try:
            sc = _apply(resolve(scenario), case)
            summary = execute(sc, work, schedule, duration, figures=True, quiet=True, dpi=dpi)
        except Exception as exc:  # one failing case must not lose the others
            summary = {"scenario": case.name, "error": f"{type(exc).__name__}: {exc}", "bearings": {}}
            written = work / "summary.json"
            if written.exists():  # a diverged run wrote its summary (with the error) and what it recorded
                import json

                summary = {**json.loads(written.read_text()), "error": summary["error"]}
        files = {str(p.relative_to(work)): p.read_bytes() for p in sorted(work.rglob("*")) if p.is_file()}
        return {"summary": summary, "files": files, "host": socket.gethostname()}
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _store(out: Path, case: Case, files: dict[str, bytes]) -> None:
    """Write a case's files into ``out/<case>`` whole: into a hidden folder first, then renamed."""
    final = out / case.name
    part = out / f".{case.name}.part"
    shutil.rmtree(part, ignore_errors=True)
    part.mkdir(parents=True)
    for rel, data in files.items():
        target = (part / rel).resolve()
        if part.resolve() not in target.parents:  # a worker is trusted to run cases, not to write anywhere
            raise ValueError(f"case {case.name}: a returned file {rel!r} points outside its folder")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    if final.exists():
        shutil.rmtree(final)
    os.replace(part, final)


def _client(scheduler: str | None, workers: int | None, connect_timeout: float, n_cases: int):
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout=connect_timeout)
        except (OSError, TimeoutError) as exc:
            raise ValueError(f"--scheduler {scheduler}: cannot reach the Dask scheduler ({exc})") from None
        except ValueError as exc:  # not an address (dask: "unknown address scheme ...")
            raise ValueError(f"--scheduler {scheduler}: not a Dask scheduler's address ({exc})") from None
        n = len(client.scheduler_info().get("workers", {}))
        return client, None, f"{scheduler}, {n} workers"
    # one process per worker, each running one case at a time: workers beyond the cases would only start and
    # idle (--workers 100000 spent minutes starting processes, then failed inside Dask)
    n = min(workers or os.cpu_count() or 1, n_cases)
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster, f"local cluster, {n} workers"


#: what a sweep writes at the top of its folder (beside one folder of run files per case, rundir.RUN_FILES, and
#: the files of its case's tables, the case's SWEEP_FILES)
SWEEP_FILES = ("sweep.csv", "sweep.json", "*.part", "*.part.png", ".*.part")


def _previous_results(out: Path, overwrite: bool, case_files=()) -> None:
    """A sweep's folder holds this sweep's results only: a non-empty one is refused (a second sweep into it left
    the first one's cases beside its own, and a sweep.csv listing only the new ones), or with ``overwrite``
    cleared, if it holds nothing but a sweep's files and case folders of run files."""
    if not out.is_dir():
        return
    old = sorted(p.name for p in out.iterdir())
    if not old:
        return
    if not overwrite:
        raise OutputFolderError(f"--out {out} is not empty ({', '.join(old[:4])}{', ...' if len(old) > 4 else ''}"
                                "): results are never mixed; give --overwrite to replace a previous sweep's "
                                "results, or another folder")

    def ours(p: Path) -> bool:
        if p.is_dir() and not p.is_symlink():
            return all(q.is_file() and is_run_file(q.name) for q in p.iterdir())
        return p.is_file() and any(fnmatch.fnmatch(p.name, pat) for pat in (*SWEEP_FILES, *case_files))

    foreign = [n for n in old if not ours(out / n)]
    if foreign:
        raise OutputFolderError(f"--overwrite: {out} holds files that are not a sweep's results "
                                f"({', '.join(foreign[:4])}): not clearing it; choose another folder")
    for n in old:
        p = out / n
        shutil.rmtree(p) if p.is_dir() else p.unlink()


def sweep(levels=None, out: Path = Path("sweep"), scenario="blade_loss", scheduler=None, schedule=None,
          duration=None, workers=None, serial=False, grid: dict[str, list[Any]] | None = None,
          progress=None, connect_timeout: float = CONNECT_TIMEOUT_S, overwrite: bool = False,
          dpi: float | None = None) -> dict:
    """Run the grid of ``levels`` (values of the scenario's level parameter, SI) x ``grid``
    (``{"comp.param": [values]}``), the cases' figures at ``dpi`` (None: the default).

    ``progress(done, total, case, result)`` is called as each case finishes. Returns the contents of
    ``sweep.json``."""
    if workers is not None and workers < 1:
        raise ValueError(f"--workers must be at least 1, got {workers}")
    out = Path(out)
    dpi = check_dpi(dpi)
    grid = dict(grid or {})
    cases = cases_of(list(levels) if levels else None, grid)
    for c in cases:  # fail early: a bad scenario, an unknown component, a duration or schedule no run takes
        check_run(_apply(resolve(scenario), c), schedule, duration)
    kind = case_kind(scenario)
    _previous_results(check_folder(out), overwrite, cases_.attribute(kind, "SWEEP_FILES", ()))
    ensure_folder(out)
    t0 = time.perf_counter()
    results: dict[str, dict] = {}

    def finished(case: Case, res: dict) -> None:
        _store(out, case, res["files"])
        results[case.name] = res
        if progress:
            progress(len(results), len(cases), case, res)

    if serial:
        where = "serial"
        for c in cases:
            finished(c, run_case(scenario, c, schedule, duration, dpi))
    else:
        from dask.distributed import as_completed

        client, cluster, where = _client(scheduler, workers, connect_timeout, len(cases))
        try:
            futures = {client.submit(run_case, scenario, c, schedule, duration, dpi, pure=False): c for c in cases}
            for fut in as_completed(futures):
                c = futures[fut]
                try:
                    res = fut.result()
                except Exception as exc:  # the worker could not run the task at all (e.g. no rotorcosim there)
                    res = {"summary": {"scenario": c.name, "error": f"{type(exc).__name__}: {exc}",
                                       "bearings": {}}, "files": {}, "host": None}
                finished(c, res)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    wall = time.perf_counter() - t0
    summaries = {c.name: results[c.name]["summary"] for c in cases}
    score = None
    tables = cases_.attribute(kind, "SWEEP_TABLES")
    if tables is not None and one_case_a_level(levels, grid):
        score = tables(out, {c.unbalance_N: summaries[c.name] for c in cases})
    _write_csv(out / "sweep.csv", cases, summaries)
    info = {"cases": [c.name for c in cases], "levels_N": list(levels or []),
            "parameters": {r: vs for r, vs in grid.items()}, "wall_time_s": wall, "executed_on": where,
            "paper_score": score,
            "case_hosts": {c.name: results[c.name].get("host") for c in cases},
            "case_wall_time_s": {c.name: summaries[c.name].get("wall_time_s") for c in cases},
            "errors": {c.name: summaries[c.name]["error"] for c in cases if summaries[c.name].get("error")}}
    write_json(out / "sweep.json", info)
    return info


def _write_csv(path: Path, cases: list[Case], summaries: dict[str, dict]) -> None:
    """One row per case: its parameters, then ``<result>_<group>`` for every numeric result of its summary's
    ``bearings`` groups (a case's results by group)."""
    params = list(dict.fromkeys(["unbalance_N"] * any(c.unbalance_N is not None for c in cases)
                                + [r for c in cases for r in c.settings]))
    results = list(dict.fromkeys(f"{key}_{brg}" for s in summaries.values()
                                 for brg, vals in s.get("bearings", {}).items() for key in vals
                                 if isinstance(vals.get(key), (int, float))))
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["case", *params, *results, "error"])
        for c in cases:
            s = summaries[c.name]
            row = [c.name] + [c.unbalance_N if p == "unbalance_N" else c.settings.get(p, "") for p in params]
            flat = {f"{k}_{b}": v for b, vals in s.get("bearings", {}).items() for k, v in vals.items()}
            row += [flat.get(r, "") for r in results] + [s.get("error") or ""]
            w.writerow(row)
    os.replace(tmp, path)


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status (1 when a case failed)."""
    levels = parse_levels(args.unbalance, cases_.attribute(case_kind(args.scenario), "LEVELS", {})) \
        if args.unbalance else None
    grid = parse_grid(args.set)
    kind = SCHEDULES[SCHEDULE_ALIASES.get(args.schedule, args.schedule)]

    def progress(done, total, case, res):
        err = res["summary"].get("error")
        wall = res["summary"].get("wall_time_s")
        state = f"failed: {err}" if err else (f"done in {wall:.3g} s" if wall else "done")
        print(f"[{done}/{total}] {case.name}: {state}", file=sys.stderr, flush=True)

    info = sweep(levels, Path(args.out), args.scenario, args.scheduler, kind, args.duration, args.workers,
                 args.serial, grid, None if args.quiet else progress, overwrite=args.overwrite, dpi=args.dpi)
    # the files at the top of the folder are this sweep's (a previous sweep's were refused or cleared)
    tables = sorted(p.name for p in Path(args.out).iterdir() if p.is_file() and p.name not in SWEEP_FILES[:2])
    print(f"{len(info['cases'])} cases in {info['wall_time_s']:.3g} s ({info['executed_on']});"
          f"{''.join(f' {t},' for t in tables)} sweep.csv and sweep.json written in {args.out}")
    score = info["paper_score"]
    line = cases_.attribute(case_kind(args.scenario), "SWEEP_SCORE")
    if score and line is not None:
        print(line(score, args.out))
    for name, e in info["errors"].items():
        print(f"  case {name} failed: {e}", file=sys.stderr)
    return 1 if info["errors"] else 0
