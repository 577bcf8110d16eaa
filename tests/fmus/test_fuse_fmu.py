"""The support fuse as an FMI 2.0 FMU in another tool (fmpy): without the master's event location it breaks inside
its own step, at the first communication point where the load is reached, and carries the soft path after."""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.fmus.export import export_component


def test_exported_fuse_breaks_at_a_communication_point(tmp_path):
    from fmpy import simulate_fmu

    path = export_component("fuse.support", tmp_path / "fuse.fmu",
                            parameters={"k_intact": 4.0e6, "break_load": 1500.0, "k_broken": 4.0e5})
    # 0.5 mm: an elastic force of 2000 N on the intact fuse, above its 1500 N break load
    res = simulate_fmu(str(path), stop_time=1e-4, output_interval=1e-5, start_values={"X[1]": 5e-4},
                       output=["broken", "F_support[1]"])
    assert res["broken"][-1] == 1.0
    after = res["broken"] == 1.0
    assert np.all(res["F_support[1]"][after] == pytest.approx(4.0e5 * 5e-4))
