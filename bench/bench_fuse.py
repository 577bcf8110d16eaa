"""The support fuse's cost: ``blade_loss_fuse`` (the paper's engine with bearing #0's housing on a fuse, 14 252 N)
against ``blade_loss_rundown``, CPU time per simulated second, all in this process (target: at most 1.2).

    python bench/bench_fuse.py [--duration 675.01] [--repeat 1]

Two comparisons, each a ratio of CPU time per simulated second:

* ``ratio_cpu_per_simulated_s``: against ``blade_loss_rundown`` at the fuse scenario's level (14 252 N), the same
  engine without the fuse: what the fuse costs;
* ``ratio_vs_shipped_rundown``: against the shipped ``blade_loss_rundown`` as it is (2 850 N).

Each run also reports its coupled (thermo-mechanical) seconds and its CPU per coupled second: a run that the
automatic schedule keeps coupled longer (a slower rundown through a crossing) costs more for that reason alone.

Each scenario runs over --duration (default the fuse scenario's own: the release, 15 s at full speed, the rundown
and 10 minutes of windmilling) on its own schedule, without recorder or figures (``simulate`` without ``out``),
after a warm-up run of 0.02 s of each (the numba caches, the reduced models); ``--repeat`` runs each that many
times and keeps the least CPU time. The fuse scenario runs without its comparison (``[results] without_fuse``:
the same rundown without the fuse, run after it, which is the other side of the ratio, not the fuse's cost). A
short --duration (0.05) checks that it works; the figure is the full one. Run it once on a quiet machine: the
machine is shared.
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import json
import time

from rotorcosim.master.api import load_scenario, simulate

#: the fuse scenario, then its comparisons: the rundown without a fuse at the fuse scenario's blade-loss level, and
#: the shipped rundown as it is
RUNS = {"blade_loss_fuse": ("blade_loss_fuse", {}),
        "blade_loss_rundown_14252N": ("blade_loss_rundown", {"rotor.F_unbalance": 14252.0}),
        "blade_loss_rundown": ("blade_loss_rundown", {})}


def scenario(name: str, changes: dict):
    """Scenario ``name`` with ``changes``, without a comparison run of its results (``without_fuse``)."""
    sc = load_scenario(name).set(changes) if changes else load_scenario(name)
    for key in ("without_fuse", "without_fuse_set"):
        sc.extra.get("results", {}).pop(key, None)
    return sc


def cost(name: str, changes: dict, duration: float, repeat: int) -> dict:
    """CPU and wall seconds of ``repeat`` runs of scenario ``name`` over ``duration`` [s] (the least of each)."""
    sc = scenario(name, changes)
    best = None
    for _ in range(repeat):
        c0, w0 = time.process_time(), time.perf_counter()
        res = simulate(sc, duration=duration, figures=False, progress=False)
        c, w = time.process_time() - c0, time.perf_counter() - w0
        if best is None or c < best["cpu_s"]:
            coupled = sum(iv["t_end"] - iv["t_start"] for iv in res.summary.get("timeline", []) if iv["phase"] == "TM")
            best = {"cpu_s": c, "wall_s": w, "engine": res.summary.get("engine"),
                    "events": len(res.summary.get("events", [])), "coupled_s": coupled}
    best["cpu_per_simulated_s"] = best["cpu_s"] / duration
    best["cpu_per_coupled_s"] = best["cpu_s"] / max(best["coupled_s"], 1e-12)
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=None, help="simulated seconds (default: the fuse scenario's)")
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args(argv)
    if a.duration is not None and not a.duration > 0.0:
        ap.error(f"--duration must be a positive number of seconds, got {a.duration}")
    if a.repeat < 1:
        ap.error(f"--repeat must be at least 1, got {a.repeat}")
    duration = a.duration or float(load_scenario("blade_loss_fuse").schedule["duration"])
    for name, changes in RUNS.values():
        simulate(scenario(name, changes), duration=0.02, figures=False, progress=False)
    out = {key: cost(name, changes, duration, a.repeat) for key, (name, changes) in RUNS.items()}
    out["duration_s"] = duration
    fuse = out["blade_loss_fuse"]["cpu_per_simulated_s"]
    out["ratio_cpu_per_simulated_s"] = fuse / out["blade_loss_rundown_14252N"]["cpu_per_simulated_s"]
    out["ratio_vs_shipped_rundown"] = fuse / out["blade_loss_rundown"]["cpu_per_simulated_s"]
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
