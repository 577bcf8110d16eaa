"""numba is imported only when the compiled path is used: a system of components without compiled kernels (here
the pure-Python two-mass system) runs in a process that never imports it, through the API's module and the
simulation alike."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

RUN = """
import sys
sys.path.insert(0, {root!r})
import rotorcosim.master.api  # noqa: F401  (the engine choice's names come without numba)
from tests.helpers.systems import two_masses
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation

sim = Simulation(two_masses())
sim.run(Timeline([Interval("TM", 0.01, 1e-3), Interval("TM", 0.01, 1e-3)]))
assert sim.engines_used == ["python", "python"], sim.engines_used
print(sorted(m for m in sys.modules if m == "numba" or m.startswith(("numba.", "llvmlite"))))
"""


def test_a_system_without_kernels_runs_without_importing_numba():
    out = subprocess.run([sys.executable, "-c", RUN.format(root=str(ROOT))], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.strip() == "[]", f"numba imported by a run without compiled kernels: {out.stdout.strip()}"
