"""The statistics of the studies: a least-squares fit's standard errors and correlations, a sample's moments and
percentiles with their confidence intervals, and sensitivity indices (Sobol' by SALib, rank correlations).

>>> import numpy as np
>>> s = summarize(np.random.default_rng(0).normal(10.0, 2.0, 4000))
>>> s["mean_ci"][0] < 10.0 < s["mean_ci"][1], s["std_ci"][0] < 2.0 < s["std_ci"][1]
(True, True)
"""
from __future__ import annotations

import math

import numpy as np

#: the confidence of every interval reported
CONFIDENCE = 0.95
#: bootstrap resamples of the standard deviation's interval
BOOTSTRAP = 2000
#: a parameter whose standard error (in its scale) exceeds this fraction of its range is "not identifiable"
UNIDENTIFIABLE = 0.5
#: harmonics of RBD-FAST's spectrum (SALib's default)
RBD_FAST_HARMONICS = 10
#: the fewest samples RBD-FAST's indices are computed from: its confidence half-width is a bootstrap on half the
#: sample, whose spectrum must reach past the harmonics (a half of 2 (M + 1) points or fewer has none beyond them:
#: every resample gives S1 = 1, the half-width 0; 20 points divide by zero in SALib's bias correction, and 24
#: samples gave first-order indices summing to 2.2 with half-widths 0)
RBD_FAST_MIN_SAMPLES = 4 * (RBD_FAST_HARMONICS + 1)
#: a parameter this close to a bound (fraction of its range in its scale) "ends at the bound"
AT_BOUND = 1e-3


def fit_errors(jac: np.ndarray, residuals: np.ndarray) -> dict:
    """Standard errors and correlations of least-squares estimates from the Jacobian ``jac`` (m x n, of the
    weighted residuals by the parameters at the optimum) and the ``residuals`` there.

    The covariance is s^2 (J^T J)^+ with s^2 = sum(r^2) / (m - n), the residual variance (Gauss-Newton; Bates &
    Watts, Nonlinear Regression Analysis, 1988, ch. 2); with m <= n, s^2 = 1 (the weights taken as 1 / the
    targets' standard deviations). Returns ``std_error`` (n), ``correlation`` (n x n), ``s2``, ``rank`` and
    ``singular_values`` of J; a direction J does not see (rank < n) gets an infinite standard error."""
    J = np.asarray(jac, dtype=float)
    r = np.asarray(residuals, dtype=float)
    m, n = J.shape
    s2 = float(r @ r / (m - n)) if m > n else 1.0
    U, sv, Vt = np.linalg.svd(J, full_matrices=False)
    tol = max(J.shape) * np.finfo(float).eps * (sv[0] if sv.size else 0.0)
    keep = sv > max(tol, 1e-12 * (sv[0] if sv.size else 0.0))
    cov = (Vt[keep].T / sv[keep] ** 2) @ Vt[keep] * s2
    se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    if not keep.all():
        # a direction of the parameters that changes no residual: the parameters it moves are undetermined
        blind = np.abs(Vt[~keep]).max(axis=0) > 1e-6
        se = np.where(blind, np.inf, se)
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    corr[~np.isfinite(corr)] = np.nan
    np.fill_diagonal(corr, 1.0)
    return {"std_error": se, "correlation": corr, "s2": s2, "rank": int(keep.sum()),
            "singular_values": sv.tolist()}


def mean_ci(x: np.ndarray, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """Student's t interval of the mean of the sample ``x``."""
    from scipy import stats

    n = len(x)
    if n < 2:
        return (math.nan, math.nan)
    half = stats.t.ppf(0.5 + confidence / 2, n - 1) * np.std(x, ddof=1) / math.sqrt(n)
    return (float(np.mean(x) - half), float(np.mean(x) + half))


def std_ci(x: np.ndarray, confidence: float = CONFIDENCE, seed: int = 0) -> tuple[float, float]:
    """A bootstrap (BCa) interval of the standard deviation of ``x`` (no normality assumed)."""
    from scipy import stats

    if len(x) < 3 or np.ptp(x) == 0:
        return (math.nan, math.nan)
    res = stats.bootstrap((x,), lambda a, axis=-1: np.std(a, ddof=1, axis=axis), confidence_level=confidence,
                          n_resamples=BOOTSTRAP, method="BCa", random_state=np.random.default_rng(seed))
    return (float(res.confidence_interval.low), float(res.confidence_interval.high))


def quantile_ci(x: np.ndarray, q: float, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """A distribution-free interval of the ``q`` quantile: the order statistics whose ranks bracket n q with
    the binomial probability ``confidence`` (Hahn & Meeker, Statistical Intervals, 1991, sec. 5.2). With too
    few samples the interval runs to the sample's minimum or maximum (then it is at least that wide)."""
    from scipy import stats

    xs = np.sort(np.asarray(x, dtype=float))
    n = len(xs)
    if n == 0:
        return (math.nan, math.nan)
    lo = int(stats.binom.ppf((1 - confidence) / 2, n, q))       # rank (1-based) of the lower order statistic
    hi = int(stats.binom.ppf(0.5 + confidence / 2, n, q)) + 1
    return (float(xs[max(lo, 1) - 1]), float(xs[min(hi, n) - 1]))


def summarize(x: np.ndarray, confidence: float = CONFIDENCE) -> dict:
    """Mean, standard deviation, 5th / 50th / 95th percentiles of the sample ``x``, each with its interval at
    ``confidence`` (``mean_ci``, ``std_ci``, ``p5_ci``...) and ``n``."""
    x = np.asarray(x, dtype=float)
    out = {"n": int(len(x)), "confidence": confidence}
    if len(x) == 0:
        return out
    out.update(mean=float(np.mean(x)), std=float(np.std(x, ddof=1)) if len(x) > 1 else math.nan,
               mean_ci=list(mean_ci(x, confidence)), std_ci=list(std_ci(x, confidence)))
    for name, q in (("p5", 0.05), ("p50", 0.50), ("p95", 0.95)):
        out[name] = float(np.percentile(x, 100 * q))
        out[f"{name}_ci"] = list(quantile_ci(x, q, confidence))
    return out


def problem(names: list[str]) -> dict:
    """SALib's problem of ``names`` on the unit hypercube (the studies map unit values to distributions)."""
    return {"num_vars": len(names), "names": list(names), "bounds": [[0.0, 1.0]] * len(names)}


def saltelli_design(names: list[str], n: int, seed: int) -> np.ndarray:
    """Saltelli's design for first-order and total Sobol' indices on the unit hypercube (SALib, on scipy's
    scrambled Sobol' sequence): ``n`` (D + 2) rows, blocks of A, AB_1..AB_D, B."""
    from SALib.sample import sobol as sobol_sample

    return sobol_sample.sample(problem(names), n, calc_second_order=False, scramble=True, seed=seed)


def sobol_indices(names: list[str], y: np.ndarray, seed: int) -> dict:
    """First-order and total Sobol' indices (with their 95 % confidence half-widths) of the outputs ``y`` of
    :func:`saltelli_design` (Saltelli 2010 / Jansen estimators, SALib ``sobol.analyze``)."""
    from SALib.analyze import sobol

    res = sobol.analyze(problem(names), np.asarray(y, dtype=float), calc_second_order=False,
                        conf_level=CONFIDENCE, seed=seed)
    return {n: {"S1": float(res["S1"][i]), "S1_conf": float(res["S1_conf"][i]), "ST": float(res["ST"][i]),
                "ST_conf": float(res["ST_conf"][i])} for i, n in enumerate(names)}


def first_order_indices(names: list[str], u: np.ndarray, y: np.ndarray, seed: int) -> dict:
    """First-order indices from any sample (random or Latin hypercube) by SALib's RBD-FAST (Plischke 2010):
    no total indices from such a sample. It needs :data:`RBD_FAST_MIN_SAMPLES` samples at least."""
    from SALib.analyze import rbd_fast

    res = rbd_fast.analyze(problem(names), np.asarray(u, dtype=float), np.asarray(y, dtype=float),
                           M=RBD_FAST_HARMONICS, conf_level=CONFIDENCE, seed=seed)
    return {n: {"S1": float(res["S1"][i]), "S1_conf": float(res["S1_conf"][i])} for i, n in enumerate(names)}


def rank_correlations(x: np.ndarray, y: np.ndarray) -> list[float]:
    """Spearman's rank correlation of the output ``y`` with each column of the inputs ``x``."""
    from scipy import stats

    out = []
    for j in range(x.shape[1]):
        if np.ptp(x[:, j]) == 0 or np.ptp(y) == 0:
            out.append(math.nan)
        else:
            out.append(float(stats.spearmanr(x[:, j], y).statistic))
    return out


def tornado(x: np.ndarray, y: np.ndarray) -> list[tuple[float, float]]:
    """For each input: the output at the input's 5th and 95th percentiles, the others at their means, from a
    linear regression of ``y`` on ``x`` (the bars of a tornado chart)."""
    A = np.column_stack([np.ones(len(y)), x])
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    mean_y = float(coef[0] + x.mean(axis=0) @ coef[1:])
    out = []
    for j in range(x.shape[1]):
        lo, hi = np.percentile(x[:, j], [5, 95])
        m = x[:, j].mean()
        out.append((mean_y + coef[j + 1] * (lo - m), mean_y + coef[j + 1] * (hi - m)))
    return out
