"""Uncertainty quantification: the results' distribution over uncertain parameters, and what they are sensitive to.

:func:`uq` reads a UQ SPEC (:mod:`.spec`), draws the samples on the unit hypercube (``"mc"``: numpy's random
generator; ``"lhs"``: scipy.stats.qmc's Latin hypercube; ``"sobol"``: Saltelli's design on scipy's scrambled
Sobol' sequence, through SALib: ``samples`` x (D + 2) runs for D parameters), maps them through each parameter's
distribution (inverse CDF) and runs them on Dask (local by default). Every sample is stored in ``samples.csv``
as it finishes: run again with the same SPEC and ``--out``, a UQ runs only the missing ones.

It writes into ``out``:

- ``samples.csv``: one row per sample: ``sample``, each parameter, each result, ``status``, ``wall_time_s``,
  ``error``, and ``recorded <comp.param>``: the value the run recorded of each sampled parameter and of every
  component parameter bound to the same engine quantity (``damperA.clearance`` and
  ``thermalA.damper_clearance`` together: master/scenario/engine.py);
- ``uq.json``: per result (``results``): ``mean``, ``std``, ``p5``, ``p50``, ``p95``, each with its 95 %
  interval (``mean_ci``...; :func:`.statistics.summarize`), ``n``; ``sobol`` (first-order ``S1`` and, with the
  sobol sampler, total ``ST`` indices with their confidence half-widths: SALib), ``rank_correlation`` (Spearman)
  and ``tornado``; ``failed`` (``count`` and the ``samples`` with their errors); ``samples``, ``status``, timings;
- ``uq_histograms.png`` and ``uq_tornado.png``.

The lognormal distribution takes the mean and standard deviation of the parameter itself (not of its log).
A sample whose run fails is counted and named under ``failed`` and left out of the statistics; with the sobol
sampler its block of the design is then left out of the Sobol' indices.

Example (see tests/master/test_study_uq.py)::

    import rotorcosim
    report = rotorcosim.uq("uq.toml", "out_dir")                # rotorcosim uq uq.toml --out out_dir
    report["results"]["final_outputs.m1.x"]["mean"], report["failed"]["count"]
"""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

from rotorcosim.components.bounded_read import read_json
from rotorcosim.master.api import load_scenario
from rotorcosim.master.run.outputs import write_json
from rotorcosim.master.scenario.engine import bound_together
from rotorcosim.master.schedule import budget
from rotorcosim.master.study import evaluate, statistics, store
from rotorcosim.master.study.spec import Distribution, UQSpec, read_uq
from rotorcosim.master.study.targets import value_of

REPORT = "uq.json"
TABLE = "samples.csv"
HISTOGRAMS = "uq_histograms.png"
#: the prefix of the columns of what a run recorded of a parameter
RECORDED = "recorded "
TORNADO = "uq_tornado.png"
#: unit-hypercube values are kept this far from 0 and 1 (an unbounded distribution's inverse CDF is infinite there)
EDGE = 1e-12


def unit_samples(sampler: str, n: int, d: int, seed: int, names: list[str] | None = None) -> np.ndarray:
    """The design on [0, 1)^d: ``n`` rows for "mc" and "lhs", ``n`` (d + 2) for "sobol" (Saltelli)."""
    from scipy.stats import qmc

    if sampler == "mc":
        u = np.random.default_rng(seed).random((n, d))
    elif sampler == "lhs":
        u = qmc.LatinHypercube(d=d, seed=seed).random(n)
    elif sampler == "sobol":
        u = statistics.saltelli_design(names or [f"x{i}" for i in range(d)], n, seed)
    else:
        raise ValueError(f"sampler {sampler!r} not in ('mc', 'lhs', 'sobol')")
    return np.clip(u, EDGE, 1 - EDGE)


def ppf(dist: Distribution, u: np.ndarray) -> np.ndarray:
    """The values of ``dist`` at the probabilities ``u`` (its inverse CDF)."""
    from scipy import stats

    v = dist.values
    if dist.distribution == "uniform":
        return v["lower"] + u * (v["upper"] - v["lower"])
    if dist.distribution == "normal":
        return stats.norm.ppf(u, loc=v["mean"], scale=v["std"])
    if dist.distribution == "lognormal":
        cv2 = (v["std"] / v["mean"]) ** 2
        return stats.lognorm.ppf(u, math.sqrt(math.log1p(cv2)), scale=v["mean"] / math.sqrt(1 + cv2))
    if dist.distribution == "truncnormal":
        a, b = (v["lower"] - v["mean"]) / v["std"], (v["upper"] - v["mean"]) / v["std"]
        return stats.truncnorm.ppf(u, a, b, loc=v["mean"], scale=v["std"])
    raise ValueError(f"distribution {dist.distribution!r} unknown")


def design(spec: UQSpec) -> tuple[np.ndarray, np.ndarray]:
    """(unit design, parameter values): the samples of ``spec``, the same for the same SPEC (seeded)."""
    names = [p.name for p in spec.parameters]
    u = unit_samples(spec.sampler, spec.samples, len(names), spec.seed, names)
    x = np.column_stack([ppf(p, u[:, j]) for j, p in enumerate(spec.parameters)])
    return u, x


def uq(spec: str | Path | UQSpec, out: str | Path, *, scheduler: str | None = None, workers: int | None = None,
       serial: bool = False, quiet: bool = False, task: Callable = evaluate.run_job, force: bool = False,
       resume: bool = False) -> dict:
    """Run the UQ of the SPEC ``spec`` (a file or a read :class:`~.spec.UQSpec`) and write its results into the
    folder ``out`` (see the module's docstring); returns uq.json's dict.

    ``scheduler``: a running Dask scheduler's address (default: a local cluster of ``workers`` processes);
    ``serial``: run in this process; ``quiet``: no progress lines (else one per sample on stderr); ``task``:
    what a run is (default :func:`.evaluate.run_job`). The folder must be new, empty, or hold this SPEC's
    interrupted UQ (then it resumes, rerunning no stored sample; ``resume``: it must). The study's wall time is
    estimated from the price of one run (as ``rotorcosim run`` prices it) and printed before the first sample;
    beyond 24 h it is refused unless ``force``."""
    t_wall = time.perf_counter()
    if not isinstance(spec, UQSpec):
        spec = read_uq(spec)
    out = Path(out)
    names = [p.name for p in spec.parameters]
    u, x = design(spec)
    if task is evaluate.run_job:   # what a run of the scenario reports and takes (a stand-in task has its own)
        check_results(spec)
        check_samples(spec, x)
    head = {"spec": str(spec.source), "scenario": spec.scenario, "duration_s": spec.duration,
            "sampler": spec.sampler, "seed": spec.seed, "samples": len(x),
            "parameters": {p.name: {"distribution": p.distribution, **p.values} for p in spec.parameters}}
    at_once = evaluate.slots(scheduler, workers, serial)   # the scheduler checked before the folder is touched
    # what each run recorded of every component parameter a sampled one moves (the engine's quantity: a damper's
    # clearance is its thermal network's too, master/scenario/engine.py)
    recorded = bound_together(load_scenario(spec.scenario), names)
    table = store.RowStore(out / TABLE, ["sample", *names, *spec.results, "status", "wall_time_s", "error",
                                         *(RECORDED + t for t in recorded)])
    stored = table.read() if (out / REPORT).is_file() and _same_study(out / REPORT, spec) else []
    done_before = {int(r["sample"]) for r in stored}
    first = next((i for i in range(len(x)) if i not in done_before), 0)
    est = evaluate.estimate(spec.scenario, [{**spec.overrides, **{n: float(x[first, j]) for j, n in enumerate(names)}}],
                            spec.duration, len(x) - len(done_before), at_once, f"uq {spec.source}",
                            "fewer samples or a shorter duration in the SPEC, or more workers (--workers, "
                            "--scheduler)", force)
    resumed = store.open_folder(out, REPORT, TABLE, spec.fingerprint(), {**head, "estimate": est},
                                spec.definition(), resume)
    print(budget.many_line(est, "uq"), file=sys.stderr, flush=True)   # once the folder is taken, before a run
    rows = {int(r["sample"]): r for r in table.read()}
    todo = [i for i in range(len(x)) if i not in rows]
    report = {**head, "estimate": est, "fingerprint": spec.fingerprint(), "definition": spec.definition(),
              "status": "running"}
    progress = evaluate.Progress(len(todo), "samples", quiet=quiet)
    if resumed and not quiet:
        print(f"resuming: {len(rows)} samples read from {out / TABLE}, {len(todo)} to run", file=sys.stderr)

    def done(k, job, summary):
        i = todo[k]
        row = {"sample": i, **{n: float(x[i, j]) for j, n in enumerate(names)},
               **{r: value_of(summary, r) for r in spec.results},
               "status": "failed" if evaluate.failed(summary) else summary.get("status"),
               "wall_time_s": summary.get("wall_time_s"), "error": summary.get("error"),
               **{RECORDED + t: recorded_value(summary, t) for t in recorded}}
        if row["status"] != "failed" and any(row[r] is None for r in spec.results):
            missing = [r for r in spec.results if row[r] is None]
            row.update(status="failed", error=f"no number at {', '.join(missing)} in the run's summary")
        table.append(row)
        rows[i] = row
        progress(job[0], row)

    jobs = [(f"sample {i}", {**spec.overrides, **{n: float(x[i, j]) for j, n in enumerate(names)}}) for i in todo]
    where = None
    try:
        with evaluate.terminate_as_interrupt(), evaluate.Evaluator(spec.scenario, spec.duration, scheduler=scheduler,
                                                                   workers=workers, serial=serial, task=task) as ev:
            ev.map(jobs, done)
            where = ev.where
    except BaseException as exc:
        report.update(status="interrupted" if isinstance(exc, KeyboardInterrupt) else "failed",
                      message=f"{type(exc).__name__}: {exc}; run again with the same SPEC and --out to resume",
                      samples_done=len(rows), wall_time_s=time.perf_counter() - t_wall)
        write_json(out / REPORT, report)
        raise
    ordered = [rows[i] for i in range(len(x))]
    table.rewrite(ordered)
    report.update(analyse(spec, u, ordered))
    report.update(status="complete", executed_on=where, resumed=resumed, samples_this_session=len(todo),
                  wall_time_s=time.perf_counter() - t_wall, figures=[HISTOGRAMS, TORNADO])
    from rotorcosim.master.study import figures

    cols = {r: [row[r] if row["status"] != "failed" else None for row in ordered] for r in spec.results}
    figures.histograms(out / HISTOGRAMS, spec.results, cols, report["results"], report["failed"], len(ordered))
    figures.tornado(out / TORNADO, spec.results, names,
                    {r: report["results"][r].get("tornado") for r in spec.results},
                    {r: report["results"][r].get("mean", 0.0) or 0.0 for r in spec.results},
                    report["failed"], len(ordered))
    write_json(out / REPORT, report)
    return report


def _same_study(report: Path, spec: UQSpec) -> bool:
    """Whether the folder's report is this SPEC's (its stored samples are then not run again)."""
    try:
        return read_json(report, REPORT).get("fingerprint") == spec.fingerprint()
    except (OSError, ValueError, AttributeError):
        return False


def check_results(spec: UQSpec) -> None:
    """Every result the SPEC names is one a run of its scenario reports (:mod:`.declared`): a SpecError naming
    the first that is not, before anything runs."""
    from rotorcosim.master.study import declared
    from rotorcosim.master.study.spec import SpecError

    sc = load_scenario(spec.scenario)
    bad = declared.refusal(sc.set(spec.overrides) if spec.overrides else sc, spec.results,
                           f"SPEC {spec.source} [uq] results")
    if bad:
        raise SpecError(bad)


def check_samples(spec: UQSpec, x: np.ndarray) -> None:
    """Every parameter's smallest and largest sampled value is one its component takes (a distribution reaching
    past a parameter's range, a normal stiffness drawn negative, would fail those samples' runs;
    :func:`.spec.check_values`): a SpecError naming the parameter, the value and its distribution, before
    anything runs."""
    from rotorcosim.master.study.spec import SpecError, check_values

    sc = load_scenario(spec.scenario)
    if spec.overrides:
        sc = sc.set(spec.overrides)
    for j, p in enumerate(spec.parameters):
        try:
            check_values(sc, p.name, (float(x[:, j].min()), float(x[:, j].max())),
                         f"SPEC {spec.source} [uq] parameter {p.name}")
        except SpecError as exc:
            vals = ", ".join(f"{k} {val:g}" for k, val in p.values.items())
            raise SpecError(f"{exc} (a sample of its {p.distribution} distribution, {vals}: narrow it or "
                            "truncate it, truncnormal)") from None


def recorded_value(summary: dict, ref: str):
    """The value run ``summary`` recorded of parameter ``ref`` (``"comp.param"``), or None."""
    comp, _, param = ref.partition(".")
    params = summary.get("provenance", {}).get("parameters", {}).get(comp, {}).get("parameters", {})
    return params.get(param)


def too_few_for_indices(n: int) -> str:
    """Why a sample of ``n`` successful runs (mc or lhs) gives no first-order indices, and what to do."""
    return (f"no sensitivity indices from {n} successful samples: RBD-FAST needs "
            f"{statistics.RBD_FAST_MIN_SAMPLES} at least ({statistics.RBD_FAST_HARMONICS} harmonics, its confidence "
            "a bootstrap on half the sample): give more samples, or sampler = \"sobol\"")


def analyse(spec: UQSpec, u: np.ndarray, rows: list[dict]) -> dict:
    """The statistics of the finished samples ``rows`` (one per design row of ``u``): see the module's docstring."""
    names = [p.name for p in spec.parameters]
    d = len(names)
    ok = np.array([r["status"] != "failed" for r in rows])
    failed = {"count": int((~ok).sum()),
              "samples": [{"sample": int(r["sample"]), "error": r.get("error")} for r in rows
                          if r["status"] == "failed"]}
    x = np.array([[float(r[n]) for n in names] for r in rows])
    stats_rows = ok.copy()
    if spec.sampler == "sobol":
        # the moments from the A and B rows of each block (independent draws); the AB rows repeat their columns
        block = np.arange(len(rows)) % (d + 2)
        stats_rows &= (block == 0) | (block == d + 1)
    out = {}
    for res in spec.results:
        y_all = np.array([np.nan if r[res] is None else float(r[res]) for r in rows])
        entry = statistics.summarize(y_all[stats_rows])
        yo, xo, uo = y_all[ok], x[ok], u[ok]
        if len(yo) > d + 1 and np.ptp(yo) > 0:
            entry["rank_correlation"] = dict(zip(names, statistics.rank_correlations(xo, yo)))
            entry["tornado"] = [list(b) for b in statistics.tornado(xo, yo)]
        if spec.sampler == "sobol":
            blocks_ok = ok.reshape(-1, d + 2).all(axis=1)
            if blocks_ok.sum() >= 2 and np.ptp(yo) > 0:
                yb = y_all.reshape(-1, d + 2)[blocks_ok].ravel()
                entry["sobol"] = {"method": "saltelli", "blocks": int(blocks_ok.sum()),
                                  "indices": statistics.sobol_indices(names, yb, spec.seed)}
        elif len(yo) >= statistics.RBD_FAST_MIN_SAMPLES and np.ptp(yo) > 0:
            entry["sobol"] = {"method": "rbd_fast", "indices": statistics.first_order_indices(names, uo, yo, spec.seed)}
        elif len(yo) > 1 and np.ptp(yo) > 0:   # (none at all: every sample failed, said in "failed")
            entry["sobol"] = {"method": "rbd_fast", "note": too_few_for_indices(len(yo))}
        out[res] = entry
    return {"results": out, "failed": failed}
