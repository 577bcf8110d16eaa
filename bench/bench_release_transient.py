"""How much of the blade release's transient the staggered run's mechanics still carry, against the monolithic
run's decay of it (docs/explanation/staggered-scheme.md, the error estimate: #0's contact loads at the low
levels).

    python bench/bench_release_transient.py [--unbalance 712] [--bearing 0] [--out DIR]

Runs ``rotorcosim compare --duration 2 --unbalance F`` (the Table 6 protocol) and reads both runs' time series:
for bearing ``--bearing``, its largest ball load's largest value less its mean over 5 revolutions (how much the
load oscillates within a revolution) at the end of each of the staggered run's thermo-mechanical intervals, and
the monolithic run's at chosen times and at the end. The staggered run's mechanics live only through its TM
intervals (32 revolutions of the 2 s), so its windows hold what is left of the release's transient at that
mechanical time, where the monolithic run has had the whole 2 s to damp it.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import json
import tempfile
from pathlib import Path

import h5py
import numpy as np

from rotorcosim.cases.blade_loss.compare import compare

#: times [s] of the monolithic run read besides its end
TIMES = (0.06, 0.12, 0.2, 0.5, 1.0)


#: the power turbine's speed of the paper's engine [rev/min]: the revolutions a window spans
RPM = 16000.0


def oscillation(series: Path, bearing: str, t_end: float, revolutions: float = 5.0, rpm: float = RPM) -> float:
    """The largest ball load's largest value less its mean [N] over ``revolutions`` ending at ``t_end``."""
    with h5py.File(series) as f:
        t = f["time"][()]
        sel = (t > t_end - revolutions * 60.0 / rpm - 1e-9) & (t <= t_end + 1e-9)
        q = f[f"bearing{bearing}.Q_max"][sel].max(axis=1)
    return float(q.max() - q.mean())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unbalance", type=float, default=712.0)
    ap.add_argument("--bearing", default="0")
    ap.add_argument("--out", default=None, help="keep the comparison here (default: a temporary folder)")
    a = ap.parse_args()
    if not (a.unbalance >= 0.0 and np.isfinite(a.unbalance)):
        ap.error(f"--unbalance must be a finite force >= 0 N, got {a.unbalance}")
    if a.bearing not in ("0", "5"):
        ap.error(f"--bearing: the paper's engine has bearings 0 and 5, got {a.bearing!r}")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(a.out) if a.out else Path(tmp) / "compare"
        compare(out, duration=2.0, unbalance=a.unbalance, figures=False, overwrite=True, timing_runs=None)
        stag, mono = out / "staggered" / "timeseries.h5", out / "monolithic" / "timeseries.h5"
        # the staggered run's TM intervals: where each ends, and the mechanical time the rotor has lived by then
        timeline = json.loads((out / "staggered" / "summary.json").read_text())["timeline"]
        tm = [(iv["t_start"], iv["t_end"]) for iv in timeline if iv["phase"] == "TM"]
        ends, mech = [e for _, e in tm], np.cumsum([e - s for s, e in tm])
        print(f"bearing #{a.bearing}, {a.unbalance:g} N: largest ball load's largest value less its mean over 5 "
              "revolutions [N]")
        for e, m in zip(ends, mech):
            print(f"staggered, end of the TM interval at {e:.3f} s (mechanical time {m:.3f} s): "
                  f"{oscillation(stag, a.bearing, e):.3f}")
        for tt in TIMES + (2.0,):
            print(f"monolithic, at {tt:g} s: {oscillation(mono, a.bearing, tt):.3f}")


if __name__ == "__main__":
    main()
