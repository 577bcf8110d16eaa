"""Model updating: a few parameters fitted to measured results by bounded nonlinear least squares.

:func:`calibrate` reads a SPEC (:mod:`.spec`) and its targets (:mod:`.targets`), and fits the parameters with
``scipy.optimize.least_squares`` (trust-region reflective, within the bounds). The search runs in each
parameter's scale mapped to [0, 1] over its range (log or linear), so that one finite-difference step, a
``diff_step`` fraction of every range, suits all of them. Each point of the search is a batch of runs, one per
fit case; the Jacobian's points (one per parameter, stepped forward, or backward at the upper bound) go to the
workers together, with the point itself already done. Every run is stored in ``evaluations.csv`` as it finishes:
a calibration run again with the same SPEC and ``--out`` reads them back and reruns none.

It writes into ``out``:

- ``calibration.json``: ``parameters`` (name -> ``value``, ``std_error``, ``start``, ``lower``, ``upper``,
  ``scale``, ``at_bound``), ``correlations``, ``fit_score`` / ``holdout_score`` (after) and ``fit_score_start``
  / ``holdout_score_start`` (before), ``targets`` (each with ours before and after), ``warnings`` (a parameter at
  a bound or not identifiable from the targets), ``status`` ("converged", "max_evaluations", "interrupted",
  "failed"), ``message``, the evaluations counted and the wall time;
- ``evaluations.csv``: one row per run: ``case``, each parameter's value, each target result of the study,
  ``status``, ``wall_time_s``, ``error``;
- ``calibration.png``: ours against the targets before and after.

The standard errors come from the Jacobian at the optimum (:func:`.statistics.fit_errors`); they are local
(linearised) and assume the residuals' scatter is the targets' (with the residual variance estimated).

Example (two masses' spring stiffnesses fitted to their final positions and velocities, as in
tests/master/test_study_calibrate.py)::

    import rotorcosim
    report = rotorcosim.calibrate("spec.toml", "out_dir")      # rotorcosim calibrate spec.toml --out out_dir
    report["parameters"]["m1.k"]["value"], report["parameters"]["m1.k"]["std_error"], report["fit_score"]
"""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

from rotorcosim.master.run.outputs import write_json
from rotorcosim.master.schedule import budget
from rotorcosim.master.study import evaluate, statistics, store
from rotorcosim.master.study.spec import CalibrationSpec, read_calibration
from rotorcosim.master.study.targets import (Target, TargetError, read_targets, residual, score, unit_warnings,
                                             value_of)

REPORT = "calibration.json"
TABLE = "evaluations.csv"
FIGURE = "calibration.png"
#: the residual of a target whose run failed or gave no usable value: log(1000) (a factor 1000 off) for log
#: residuals, 1000 times the target for linear ones (before the weight): large, finite, steering away from it
FAILED_FACTOR = 1000.0


class Fit:
    """The runs of a calibration: points of the parameters (unit scale) -> results, run in batches on the
    evaluator and stored; :meth:`residuals` and :meth:`jacobian` for ``least_squares``."""

    def __init__(self, spec: CalibrationSpec, targets: list[Target], ev: evaluate.Evaluator,
                 table: store.RowStore, log: Callable[[str], None], quiet: bool):
        self.spec, self.targets, self.ev, self.table, self.log, self.quiet = spec, targets, ev, table, log, quiet
        self.params = spec.parameters
        self.fit = [t for t in targets if not t.holdout]
        self.fit_cases = list(dict.fromkeys(t.case for t in self.fit))
        self.all_cases = list(dict.fromkeys(t.case for t in targets))
        self.results = list(dict.fromkeys(t.result for t in targets))
        self.known: dict[tuple, dict] = {}
        self.run_now = 0
        self.u0 = np.array([p.to_unit(p.start) for p in self.params])
        for row in table.read():
            key = (row["case"] or "", *(repr(float(row[p.name])) for p in self.params))
            self.known[key] = row

    def values(self, u) -> list[float]:
        """The parameters' values at ``u`` (unit scale); the start exactly where u is the start's."""
        return [p.start if ui == u0 else p.from_unit(float(ui)) for p, ui, u0 in zip(self.params, u, self.u0)]

    def _key(self, case: str, vals) -> tuple:
        return (case, *(repr(float(v)) for v in vals))

    def run(self, points: list, cases: list[str]) -> None:
        """Make sure every (point, case) has been run: the missing ones in one batch."""
        jobs, keys = [], []
        for u in points:
            vals = self.values(u)
            for c in cases:
                k = self._key(c, vals)
                if k in self.known or k in keys:
                    continue
                keys.append(k)
                over = {**self.spec.cases.get(c, {}), **{p.name: v for p, v in zip(self.params, vals)}}
                label = f"{c or 'scenario'} " + " ".join(f"{p.name}={v:.5g}" for p, v in zip(self.params, vals))
                jobs.append((label, over))
        if not jobs:
            return
        progress = evaluate.Progress(len(jobs), "runs of this batch", quiet=self.quiet)

        def done(i, job, summary):
            k = keys[i]
            row = {"case": k[0], **{p.name: float(v) for p, v in zip(self.params, k[1:])},
                   **{r: value_of(summary, r) for r in self.results},
                   "status": "failed" if evaluate.failed(summary) else summary.get("status"),
                   "wall_time_s": summary.get("wall_time_s"), "error": summary.get("error")}
            self.table.append(row)
            self.known[k] = row
            self.run_now += 1
            progress(job[0], summary)

        self.ev.map(jobs, done)

    def ours(self, u, targets: list[Target]) -> list[float | None]:
        """Our value of each target at ``u`` (None where its run failed)."""
        vals = self.values(u)
        out = []
        for t in targets:
            row = self.known[self._key(t.case, vals)]
            v = row.get(t.result)
            out.append(None if row.get("status") == "failed" or v is None else float(v))
        return out

    def residuals(self, u) -> np.ndarray:
        """The weighted residuals of the fit targets at ``u``."""
        self.run([u], self.fit_cases)
        failed = math.log(FAILED_FACTOR) if self.spec.residual == "log" else None
        out = []
        for t, v in zip(self.fit, self.ours(u, self.fit)):
            f = failed if failed is not None else FAILED_FACTOR * max(abs(t.value), 1.0)
            out.append(residual(t, v, self.spec.residual, f))
        return np.array(out)

    def steps(self, u) -> list[float]:
        """The finite-difference step of each parameter at ``u``: forward, backward where forward leaves [0, 1]."""
        h = self.spec.diff_step
        return [h if ui + h <= 1.0 else -h for ui in u]

    def jacobian(self, u) -> np.ndarray:
        """d residuals / d u by forward differences, the n stepped points run together."""
        u = np.asarray(u, dtype=float)
        hs = self.steps(u)
        pts = []
        for j, h in enumerate(hs):
            v = u.copy()
            v[j] += h
            pts.append(v)
        self.run([u, *pts], self.fit_cases)
        r0 = self.residuals(u)
        return np.column_stack([(self.residuals(v) - r0) / h for v, h in zip(pts, hs)])


def calibrate(spec: str | Path | CalibrationSpec, out: str | Path, *, scheduler: str | None = None,
              workers: int | None = None, serial: bool = False, quiet: bool = False,
              log: Callable[[str], None] | None = None, task: Callable = evaluate.run_job, force: bool = False,
              resume: bool = False) -> dict:
    """Fit the parameters of the SPEC ``spec`` (a file or a read :class:`~.spec.CalibrationSpec`) to its targets
    and write the results into the folder ``out`` (see the module's docstring); returns calibration.json's dict.

    ``scheduler``: a running Dask scheduler's address (default: a local cluster of ``workers`` processes);
    ``serial``: run in this process; ``quiet``: no progress lines (else one per run on stderr, and ``log`` (a
    function of one line, default: print to stderr) for the search's steps); ``task``: what a run is (default
    :func:`.evaluate.run_job`). The folder must be new, empty, or hold this SPEC's interrupted calibration (then
    it resumes, rerunning no stored run; ``resume``: it must). Every target's result is checked against what a
    run of its case reports before anything runs; the study's wall time (at most ``max_evaluations`` points of the
    search, each a run per parameter and fit case) is estimated from the price of one run of each case (as
    ``rotorcosim run`` prices it), printed before the first run and refused beyond 24 h unless ``force``."""
    from scipy.optimize import least_squares

    t_wall = time.perf_counter()
    if not isinstance(spec, CalibrationSpec):
        spec = read_calibration(spec)
    say = log or (lambda line: print(line, file=sys.stderr, flush=True))
    if quiet:
        say = lambda line: None  # noqa: E731 - the quiet twin of the print below
    targets = read_targets(spec.targets, spec.cases, spec.residual)
    out = Path(out)
    head = {"spec": str(spec.source), "scenario": spec.scenario, "duration_s": spec.duration,
            "residual": spec.residual}
    if task is evaluate.run_job:   # what a run of the scenario reports (a stand-in task has its own)
        check_target_results(spec, targets)
    at_once = evaluate.slots(scheduler, workers, serial)   # the scheduler checked before the folder is touched
    fit_cases = list(dict.fromkeys(t.case for t in targets if not t.holdout))
    all_cases = list(dict.fromkeys(t.case for t in targets))
    runs = spec.max_evaluations * (1 + len(spec.parameters)) * len(fit_cases) + 2 * len(all_cases)
    start = {p.name: p.start for p in spec.parameters}
    est = evaluate.estimate(spec.scenario, [{**spec.cases.get(c, {}), **start} for c in all_cases], spec.duration,
                            runs, at_once, f"calibrate {spec.source} (at most)",
                            "a smaller max_evaluations, fewer cases or a shorter duration in the SPEC, or more "
                            "workers (--workers, --scheduler)", force)
    est["runs_at_most"] = True   # the search may stop long before max_evaluations
    resumed = store.open_folder(out, REPORT, TABLE, spec.fingerprint(), {**head, "estimate": est},
                                spec.definition(), resume)
    print(budget.many_line(est, "calibrate"), file=sys.stderr, flush=True)   # once the folder is taken
    results = list(dict.fromkeys(t.result for t in targets))
    table = store.RowStore(out / TABLE, ["case", *(p.name for p in spec.parameters), *results, "status",
                                         "wall_time_s", "error"])
    with evaluate.terminate_as_interrupt(), evaluate.Evaluator(spec.scenario, spec.duration, scheduler=scheduler,
                                                               workers=workers, serial=serial, task=task) as ev:
        fit = Fit(spec, targets, ev, table, say, quiet)
        if resumed:
            say(f"resuming: {len(fit.known)} runs read from {out / TABLE}")
        report = {**head, "estimate": est, "fingerprint": spec.fingerprint(), "definition": spec.definition(),
                  "status": "running"}
        try:
            # the start, every case (fit and holdout): the scores before, and a check that every target exists
            fit.run([fit.u0], fit.all_cases)
            _check_results(fit, targets)
            slips = unit_warnings(targets, fit.ours(fit.u0, targets))
            for line in slips:
                say(f"warning: {line}")
            r_start = fit.residuals(fit.u0)
            say(f"start: cost {0.5 * float(r_start @ r_start):.6g} over {len(r_start)} fit targets")
            n_it = [0]

            def fun(u):
                r = fit.residuals(u)
                n_it[0] += 1
                vals = ", ".join(f"{p.name}={v:.5g}" for p, v in zip(spec.parameters, fit.values(u)))
                say(f"point {n_it[0]}: cost {0.5 * float(r @ r):.6g} at {vals}")
                return r

            res = least_squares(fun, fit.u0, jac=fit.jacobian, bounds=(0.0, 1.0), method="trf", x_scale=1.0,
                                max_nfev=spec.max_evaluations, ftol=spec.tolerance, xtol=spec.tolerance,
                                gtol=spec.tolerance)
            u = np.clip(res.x, 0.0, 1.0)
            fit.run([u], fit.all_cases)
            status = "converged" if res.status > 0 else ("max_evaluations" if res.status == 0 else "failed")
            report.update(_report(spec, fit, targets, u, fit.residuals(u), fit.jacobian(u), status, res.message))
            report["warnings"] = slips + report["warnings"]
        except KeyboardInterrupt:
            report.update(status="interrupted", message="interrupted: run again with the same SPEC and --out to "
                                                        "resume (no stored run is repeated)")
            raise
        except Exception as exc:
            report.update(status="failed", message=f"{type(exc).__name__}: {exc}")
            raise
        finally:
            report.update(evaluations=len(fit.known), evaluations_this_session=fit.run_now,
                          resumed=resumed, executed_on=ev.where, wall_time_s=time.perf_counter() - t_wall)
            write_json(out / REPORT, report)
    rows = sorted(table.read(), key=lambda r: (r["case"] or "",
                                                *(float(r[p.name]) for p in spec.parameters)))
    table.rewrite(rows)
    from rotorcosim.master.study import figures

    figures.calibration_figure(out / FIGURE, report)
    report["figure"] = FIGURE
    write_json(out / REPORT, report)
    return report


def check_target_results(spec: CalibrationSpec, targets: list[Target]) -> None:
    """Every target's result is one a run of its case reports (:mod:`.declared`): a TargetError naming the first
    that is not, before anything runs."""
    from rotorcosim.master.api import load_scenario
    from rotorcosim.master.study import declared

    base = load_scenario(spec.scenario)
    for case in dict.fromkeys(t.case for t in targets):
        sc = base.set(spec.cases[case]) if spec.cases.get(case) else base
        bad = declared.refusal(sc, [t.result for t in targets if t.case == case],
                               f"targets file {spec.targets}" + (f" case {case!r}" if case else ""))
        if bad:
            raise TargetError(bad)


def _check_results(fit: Fit, targets: list[Target]) -> None:
    """Every target's result exists in its case's summary at the start (else the target names nothing)."""
    vals = fit.values(fit.u0)
    for t in targets:
        row = fit.known[fit._key(t.case, vals)]
        if row.get("status") == "failed":
            raise RuntimeError(f"case {t.case or 'scenario'!r} failed at the start values: {row.get('error')}")
        if row.get(t.result) is None:
            raise TargetError(f"target {t.label}: the run's summary has no number at {t.result!r}")


def _report(spec: CalibrationSpec, fit: Fit, targets: list[Target], u, r, J, status: str, message: str) -> dict:
    errs = statistics.fit_errors(J, r)
    vals = fit.values(u)
    names = [p.name for p in spec.parameters]
    params, warnings = {}, []
    for j, (p, v) in enumerate(zip(spec.parameters, vals)):
        se_u = float(errs["std_error"][j])
        at = "lower" if u[j] <= statistics.AT_BOUND else "upper" if u[j] >= 1 - statistics.AT_BOUND else None
        params[p.name] = {"value": v, "std_error": se_u * p.d_value_d_unit(v) if math.isfinite(se_u) else None,
                          "std_error_unit_range": se_u if math.isfinite(se_u) else None,
                          "start": p.start, "lower": p.lower, "upper": p.upper, "scale": p.scale, "at_bound": at}
        if at:
            warnings.append(f"{p.name} ends at its {at} bound ({v:.6g}): the targets would take it further; its "
                            f"standard error is not meaningful there")
        if not math.isfinite(se_u) or se_u > statistics.UNIDENTIFIABLE:
            warnings.append(f"{p.name} is not identifiable from the targets (standard error "
                            f"{'infinite' if not math.isfinite(se_u) else f'{se_u:.2g} of its range'})")
    corr = errs["correlation"]
    for i in range(len(names)):
        for k in range(i + 1, len(names)):
            if math.isfinite(corr[i, k]) and abs(corr[i, k]) > 0.95:
                warnings.append(f"{names[i]} and {names[k]} are correlated ({corr[i, k]:+.3f}): the targets fix "
                                f"a combination of them rather than each")
    fit_t = [t for t in targets if not t.holdout]
    hold_t = [t for t in targets if t.holdout]
    before, after = fit.ours(fit.u0, targets), fit.ours(u, targets)
    pick = lambda ts, vs: [v for t, v in zip(targets, vs) if t in ts]  # noqa: E731 - a one-line selector, used twice
    r0 = fit.residuals(fit.u0)
    return {
        "status": status, "message": message, "parameters": params,
        "correlations": {a: {b: (None if not math.isfinite(corr[i, k]) else float(corr[i, k]))
                             for k, b in enumerate(names)} for i, a in enumerate(names)},
        "fit_score": score(fit_t, pick(fit_t, after)), "holdout_score": score(hold_t, pick(hold_t, after)),
        "fit_score_start": score(fit_t, pick(fit_t, before)),
        "holdout_score_start": score(hold_t, pick(hold_t, before)),
        "cost_start": 0.5 * float(r0 @ r0), "cost": 0.5 * float(r @ r), "residual_variance": errs["s2"],
        "jacobian_rank": errs["rank"], "warnings": warnings,
        "targets": [{"case": t.case, "result": t.result, "value": t.value, "weight": t.weight,
                     "holdout": t.holdout, "start": b, "final": a} for t, b, a in zip(targets, before, after)],
    }
