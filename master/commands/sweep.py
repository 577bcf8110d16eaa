"""``rotorcosim sweep --unbalance LIST --out DIR [--scheduler ADDRESS]``: blade-loss levels in parallel on Dask.

Each level runs the blade-loss scenario (``rotorcosim run`` with ``--unbalance``) in its own folder
``DIR/F_<N>``; the sweep then writes ``DIR/table5.csv`` in the format of the paper's Table 5
(``result,bearing,<F_u>...``) and ``DIR/table5.md``: our value beside the paper's, cell by cell.
Without ``--scheduler`` a local Dask cluster (one single-threaded worker process per core) runs the cases.
"""
from __future__ import annotations

import csv
import time
from pathlib import Path

from rotorcosim.master.outputs import write_json

from .run import apply_unbalance, execute, resolve
from .table5 import PAPER_LEVELS, paper_table5, write_table5

def add_arguments(p):
    p.add_argument("--unbalance", required=True,
                   help="comma-separated blade-loss forces [N], or 'paper' for the seven levels of Table 5")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (default: a local cluster)")
    p.add_argument("--scenario", default="blade_loss", help="the scenario every level runs (default blade_loss)")
    p.add_argument("--duration", type=float, default=None, help="simulated duration [s] (cuts the timeline)")
    p.add_argument("--schedule", choices=["paper", "auto", "monolithic"], default="paper")
    p.add_argument("--workers", type=int, default=None, help="local cluster size (default: number of cores)")
    p.add_argument("--serial", action="store_true", help="run the levels one after another, without Dask")


def parse_levels(text: str) -> list[float]:
    if text.strip().lower() == "paper":
        return list(PAPER_LEVELS)
    out = []
    for item in text.replace(" ", ",").split(","):
        if not item:
            continue
        try:
            f = float(item)
        except ValueError:
            raise ValueError(f"--unbalance: {item!r} is not a number") from None
        if not (f >= 0 and f < float("inf")):
            raise ValueError(f"--unbalance: {item!r} must be a finite force >= 0 N")
        out.append(f)
    if not out:
        raise ValueError("--unbalance: no level given")
    if len(set(out)) != len(out):
        raise ValueError("--unbalance: a level is repeated")
    return out


def run_case(scenario: str, force: float, out: str, schedule: str | None, duration: float | None) -> dict:
    """One level (runs in a Dask worker): returns its summary."""
    sc = resolve(scenario)
    apply_unbalance(sc, force)
    try:
        return execute(sc, Path(out), schedule, duration, figures=True, quiet=True)
    except Exception as exc:  # one diverging level must not lose the others
        return {"scenario": sc.name, "error": f"{type(exc).__name__}: {exc}", "bearings": {}}


def sweep(levels, out: Path, scenario="blade_loss", scheduler=None, schedule=None, duration=None,
          workers=None, serial=False) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    resolve(scenario)  # fail early on a bad scenario
    jobs = [(scenario, f, str(out / f"F_{f:g}"), schedule, duration) for f in levels]
    t0 = time.perf_counter()
    if serial:
        results = [run_case(*j) for j in jobs]
        where = "serial"
    else:
        from dask.distributed import Client, LocalCluster

        if scheduler:
            client = Client(scheduler)
            cluster = None
            where = scheduler
        else:
            import os

            n = workers or os.cpu_count() or 1
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
            client = Client(cluster)
            where = f"local cluster, {n} workers"
        try:
            futures = [client.submit(run_case, *j, pure=False) for j in jobs]
            results = client.gather(futures)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    wall = time.perf_counter() - t0
    by_level = dict(zip(levels, results))
    write_table5(out, by_level)
    info = {"levels_N": levels, "wall_time_s": wall, "executed_on": where,
            "case_wall_time_s": {f"{f:g}": r.get("wall_time_s") for f, r in by_level.items()},
            "errors": {f"{f:g}": r["error"] for f, r in by_level.items() if r.get("error")}}
    write_json(out / "sweep.json", info)
    return info


def run(args) -> int:
    levels = parse_levels(args.unbalance)
    kind = {"paper": None, "auto": "auto", "monolithic": "monolithic"}[args.schedule]
    info = sweep(levels, Path(args.out), args.scenario, args.scheduler, kind, args.duration, args.workers, args.serial)
    print(f"{len(levels)} levels in {info['wall_time_s']:.3g} s ({info['executed_on']}); "
          f"{args.out}/table5.csv and table5.md written")
    for f, e in info["errors"].items():
        print(f"  level {f} N failed: {e}")
    return 1 if info["errors"] else 0
