"""The studies' runs: cost per evaluation and parallel efficiency of the local Dask cluster, and the engine's
synthetic-truth recovery by ``calibrate``.

    python bench/bench_study.py [--jobs 8] [--workers 2] [--duration 120] [--truth]

Part 1 runs ``--jobs`` blade-loss runs (2850 N, the O-ring of damper #0 varied by +-5 %) one after another in this
process and then on a local cluster of ``--workers`` processes, and prints the wall time per evaluation of each
and the parallel efficiency, serial time / (workers x Dask time). Measured in one process, one after the other: on a
machine shared with other jobs the efficiency also measures the load.

Part 2 (``--truth``): a synthetic truth on the engine: targets made by the engine itself at 2850 N, 2 s
runs, with damper #0's O-ring at 5.8e6 N/m and bearing #0's Palmgren factor at 1.4; the calibration starts at
5.254e6 N/m and 1.0 and must end within 1 % (or within its standard error) of both.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import tempfile
import time
from pathlib import Path

from rotorcosim.master.study.evaluate import Evaluator

SCENARIO = "blade_loss_2850"


def efficiency(jobs: int, workers: int, duration: float | None) -> None:
    items = [(f"k{i}", {"damper0.k_spring": 5.254e6 * (0.95 + 0.1 * i / max(1, jobs - 1))}) for i in range(jobs)]
    with Evaluator(SCENARIO, duration, serial=True) as ev:
        ev.map(items[:1])                              # warm the caches (numba, engine data) in this process
        t0 = time.perf_counter()
        ser = ev.map(items)
        t_ser = time.perf_counter() - t0
    with Evaluator(SCENARIO, duration, workers=workers) as ev:
        ev.map(items[:workers])                        # start the workers and warm them
        t0 = time.perf_counter()
        par = ev.map(items)
        t_par = time.perf_counter() - t0
        where = ev.where
    bad = [s.get("error") for s in ser + par if s.get("error")]
    length = f"{duration:g} s" if duration else "full duration"
    print(f"{jobs} runs of {SCENARIO} ({length}): serial {t_ser / jobs:.2f} s per evaluation, Dask "
          f"({where}) {t_par / jobs:.2f} s per evaluation; parallel efficiency {t_ser / (workers * t_par):.2f}"
          + (f"; {len(bad)} failed: {bad[0]}" if bad else ""))


def truth() -> None:
    import rotorcosim

    true = {"damper0.k_spring": 5.8e6, "bearing0.f0": 1.4}
    res = ["bearings.0.whirl_amplitude_mm", "bearings.0.transmissibility", "bearings.0.sfd_power_W",
           "bearings.0.drag_power_W", "bearings.0.max_contact_load_N"]
    from rotorcosim.master.study.targets import value_of

    s = rotorcosim.simulate(rotorcosim.load_scenario(SCENARIO).set(true), duration=2.0, record=[],
                            figures=False).summary
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        (d / "targets.csv").write_text("case,result,value\n" + "".join(f",{r},{value_of(s, r)!r}\n" for r in res))
        (d / "spec.toml").write_text(f'''[calibrate]
scenario = "{SCENARIO}"
duration = 2.0
targets = "targets.csv"
[[calibrate.parameter]]
name = "damper0.k_spring"
lower = 3.0e6
upper = 1.0e7
start = 5.254e6
scale = "log"
[[calibrate.parameter]]
name = "bearing0.f0"
lower = 0.5
upper = 3.0
start = 1.0
scale = "log"
''')
        t0 = time.perf_counter()
        rep = rotorcosim.calibrate(d / "spec.toml", d / "out", quiet=True)
        wall = time.perf_counter() - t0
    for name, v in true.items():
        p = rep["parameters"][name]
        err = abs(p["value"] / v - 1)
        ok = err < 0.01 or abs(p["value"] - v) <= (p["std_error"] or 0)
        print(f"{name}: truth {v:.6g}, found {p['value']:.6g} +- {p['std_error']:.3g} ({100 * err:.3f} % off): "
              f"{'recovered' if ok else 'NOT recovered'}")
    print(f"{rep['status']} after {rep['evaluations']} runs in {wall:.1f} s; warnings: {rep['warnings']}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--duration", type=float, default=None, help="run duration in s (default: the scenario's)")
    ap.add_argument("--truth", action="store_true", help="also the synthetic-truth calibration of the engine")
    a = ap.parse_args()
    efficiency(a.jobs, a.workers, a.duration)
    if a.truth:
        truth()
