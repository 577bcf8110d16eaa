"""An FMI 3.0 co-simulation FMU (built here with pythonfmu3, another tool than our exporter) as a component."""
from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from rotorcosim.fmus.importer import FMUError, load_fmu_component

MODEL = textwrap.dedent('''
    from pythonfmu3 import Fmi3Slave, Fmi3Causality, Fmi3Variability, Float64


    class osc3(Fmi3Slave):
        """x'' = -k x + F by semi-implicit Euler; the state is the vector X = (x, v)."""

        def __init__(self, **kwargs):
            super().__init__(**kwargs)
            self.k, self.F, self.x, self.time = 4.0, 0.0, [1.0, 0.0], 0.0
            self.register_variable(Float64("time", causality=Fmi3Causality.independent,
                                           variability=Fmi3Variability.continuous))
            self.register_variable(Float64("k", causality=Fmi3Causality.parameter,
                                           variability=Fmi3Variability.tunable, start=4.0, unit="N/m"))
            self.register_variable(Float64("F", causality=Fmi3Causality.input, start=0.0))
            for i in range(2):
                self.register_variable(Float64(f"X[{i + 1}]", causality=Fmi3Causality.output,
                                               getter=(lambda i=i: self.x[i])))

        def do_step(self, current_time, step_size):
            self.x[1] += step_size * (-self.k * self.x[0] + self.F)
            self.x[0] += step_size * self.x[1]
            return True
''')


@pytest.fixture(scope="module")
def fmi3_fmu(tmp_path_factory):
    d = tmp_path_factory.mktemp("fmi3")
    (d / "osc3.py").write_text(MODEL)
    out = subprocess.run([sys.executable, "-m", "pythonfmu3", "build", "-f", "osc3.py", "-d", str(d)], cwd=d,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    return d / "osc3.fmu"


def expected(k: float, F: float, h: float, n: int) -> np.ndarray:
    x, v = 1.0, 0.0
    for _ in range(n):
        v += h * (-k * x + F)
        x += h * v
    return np.array([x, v])


def test_fmi3_fmu_regrouped_and_stepped(fmi3_fmu):
    c = load_fmu_component(fmi3_fmu, "osc", {"k": 9.0})
    try:
        ports = {v.name: (v.causality, v.size) for v in c.variables}
        assert ports == {"k": ("parameter", 1), "F": ("input", 1), "X": ("output", 2)}
        assert c.variable("k").unit == "N/m" and c.phases == frozenset({"TM"})
        c.setup(0.0)
        h = 1e-2
        for k in range(50):
            c.set_inputs({"F": [0.5]})
            c.do_step(k * h, h)
        np.testing.assert_allclose(c.y["X"], expected(9.0, 0.5, h, 50), rtol=1e-12)
        # pythonfmu3's FMUs do not offer FMU state: rollback is refused clearly
        with pytest.raises(FMUError, match="cannot get/set its state"):
            c.get_state()
    finally:
        c.terminate()
