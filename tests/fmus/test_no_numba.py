"""An FMU-only system runs without importing numba (numba is imported only when the compiled path is used)."""
from __future__ import annotations

import subprocess
import sys


RUN = """
import sys
from rotorcosim.master.scenario.build import build_simulation, parse
from rotorcosim.master.schedule import Interval, Timeline

inputs = {{"u": 25.0, "ui": 4, "ub": False, "us": "b", "ue": 1, "ul": -7, "uu": 5, "ua": [1.0, 2.0, 3.0]}}
sc = parse({{"components": {{"f": {{"fmu": {fmu!r}}}}}, "inputs": {{f"f.{{k}}": v for k, v in inputs.items()}}}})
sim = build_simulation(sc, [])
try:
    sim.run(Timeline([Interval("TM", 0.5, 0.125)]))
finally:
    for c in sim.system.components.values():
        c.terminate()
print(sorted(m for m in sys.modules if m == "numba" or m.startswith(("numba.", "llvmlite"))))
"""


def test_an_fmu_only_system_runs_without_importing_numba(types3_fmu):
    out = subprocess.run([sys.executable, "-c", RUN.format(fmu=str(types3_fmu))], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.strip() == "[]", f"numba imported by an FMU-only run: {out.stdout.strip()}"
