"""What the event machinery costs, in this process: two ratios of CPU time.

    python bench/bench_events.py [--duration 1.0] [--fuse-duration 0.5] [--repeat 3]

1. **Armed against not armed** (the compiled loop, no event happening): the main job's scenario over --duration on
   a monolithic schedule, as it is and with the event machinery armed by a time event beyond the run's end
   (``damper0.oil_loss_time`` = 1e6 s: every coupled interval builds its event locator and asks it for the next
   time event before each compiled run). The runs alternate, ``--repeat`` each, the least CPU time of each kept;
   the ratio is armed / not armed (1.0: no measurable cost).
2. **jeffcott_fuse compiled against generic** over --fuse-duration (the break at 0.018 s located in both): CPU
   time generic / compiled, and whether the two located the same break.

Each run goes without recorder or figures (``simulate`` without ``out``) after a warm-up of 0.02 s (the numba
caches, the reduced models). Run it on a quiet machine: the machine is shared.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import json
import time

from rotorcosim.master.api import load_scenario, simulate


def _cpu(sc, duration: float, engine: str = "auto") -> tuple[float, dict]:
    c0 = time.process_time()
    res = simulate(sc, duration=duration, schedule="monolithic", figures=False, progress=False, engine=engine)
    return time.process_time() - c0, res.summary


def armed(duration: float, repeat: int) -> dict:
    """The main job's scenario, not armed and armed (module docstring, 1)."""
    plain = load_scenario(None)
    armed_sc = plain.set({"damper0.oil_loss_time": 1.0e6})
    for sc in (plain, armed_sc):
        _cpu(sc, 0.02)
    best = {"not_armed": None, "armed": None}
    for _ in range(repeat):
        for key, sc in (("not_armed", plain), ("armed", armed_sc)):
            c, summary = _cpu(sc, duration)
            assert summary["engine"] == "compiled" and not summary.get("events")
            best[key] = c if best[key] is None else min(best[key], c)
    return {"duration_s": duration, "cpu_s": best, "ratio_armed": best["armed"] / best["not_armed"]}


def fuse(duration: float, repeat: int) -> dict:
    """jeffcott_fuse, compiled and generic (module docstring, 2)."""
    sc = load_scenario("jeffcott_fuse")
    out = {}
    for engine in ("compiled", "python"):
        _cpu(sc, 0.02, engine)
        runs = [_cpu(sc, duration, engine) for _ in range(repeat)]
        c = min(r[0] for r in runs)
        out[engine] = {"cpu_s": c, "events": [e["t_s"] for e in runs[0][1]["events"]]}
    out["duration_s"] = duration
    out["ratio_generic_over_compiled"] = out["python"]["cpu_s"] / out["compiled"]["cpu_s"]
    out["same_events"] = out["python"]["events"] == out["compiled"]["events"]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=1.0, help="simulated seconds of the main job's scenario")
    ap.add_argument("--fuse-duration", type=float, default=0.5, help="simulated seconds of jeffcott_fuse")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    print(json.dumps({"armed": armed(a.duration, a.repeat), "jeffcott_fuse": fuse(a.fuse_duration, a.repeat)},
                     indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
