"""What running an FMU in its own process costs: the mass FMU + a native spring, in process and out of process.

    python bench/bench_fmu_process.py [--steps 2000]

Prints the wall time per base step of each (the difference is one pipe round trip per FMU step).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import tempfile
import time
from pathlib import Path

from rotorcosim.components.registry import create
from rotorcosim.fmus.export import export_component
from rotorcosim.fmus.importer import load_fmu_component
from rotorcosim.fmus.process import ProcessFMU
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=2000)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        fmu = export_component("testing.mass", Path(tmp) / "mass.fmu", instance_name="m1", parameters={"k": 40.0})
        for kind in ("in process", "out of process"):
            m = load_fmu_component(fmu, "m", {}) if kind == "in process" else ProcessFMU(fmu, "m", {}, timeout=60)
            s = System({"m": m, "s": create("testing.spring", "s")},
                       [Connection("m.x", "s.x_in"), Connection("m.v", "s.v_in"), Connection("s.F", "m.F")])
            sim = Simulation(s)
            t0 = time.perf_counter()
            sim.run(Timeline([Interval("TM", a.steps * 1e-3, 1e-3)]))
            w = time.perf_counter() - t0
            print(f"{kind}: {w / a.steps * 1e6:.0f} us per base step (FMU + native spring)")
            m.terminate()


if __name__ == "__main__":
    main()
