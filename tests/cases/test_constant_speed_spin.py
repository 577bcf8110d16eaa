"""Speed as a state reproduces the constant-speed engine bit for bit: blade_loss_2850 through the speed-following
rotor, bearings and rub rings, fed by spools at a constant 16 000 / 15 000 rev/min, records exactly the numbers
of the constant-speed components (the reference: the shipped scenario itself)."""
from __future__ import annotations

import numpy as np

from rotorcosim.master.api import simulate

SPIN = '''
connections = [
  { from = "spool_pt.Omega", to = "rotor.Omega_pt" }, { from = "spool_pt.dOmega", to = "rotor.dOmega_pt" },
  { from = "spool_gg.Omega", to = "rotor.Omega_gg" },
  { from = "spool_pt.Omega", to = "bearing0.Omega" }, { from = "spool_pt.Omega", to = "bearing5.Omega" },
  { from = "spool_pt.Omega", to = "rubring0.Omega" }, { from = "spool_pt.Omega", to = "rubring5.Omega" },
  { from = "bearing0.T_drag", to = "spool_pt.T_drag1" }, { from = "bearing5.T_drag", to = "spool_pt.T_drag2" },
  { from = "rubring0.T_rub", to = "spool_pt.T_rub1" }, { from = "rubring5.T_rub", to = "spool_pt.T_rub2" },
]
[scenario]
extends = "blade_loss_5700"
name = "spin_constant"
[inputs]
"spool_gg.T_drag1" = 0.0
"spool_gg.T_drag2" = 0.0
"spool_gg.T_rub1" = 0.0
"spool_gg.T_rub2" = 0.0
[components.spool_pt]
implementation = "spool.speed"
parameters = { profile = "constant", speed_rpm = "engine:spool.pt.speed_rpm", inertia = "engine:spool.pt.inertia" }
[components.spool_gg]
implementation = "spool.speed"
parameters = { profile = "constant", speed_rpm = "engine:spool.gg.speed_rpm", inertia = "engine:spool.gg.inertia", spool = "gg" }
[components.rotor]
implementation = "rotor.mta_spinning"
[components.bearing0]
implementation = "bearing.hertz_spinning"
[components.bearing5]
implementation = "bearing.hertz_spinning"
[components.rubring0]
implementation = "rubring.contact_spinning"
[components.rubring5]
implementation = "rubring.contact_spinning"
[algorithm]
order = ["spool_pt", "spool_gg", "rotor", "bearing0", "bearing5", "damper0", "damper5", "rubring0", "rubring5",
         "thermal0", "thermal5"]
'''


def test_constant_profile_is_bit_identical(tmp_path):
    """5700 N (rubbing), 0.3 s: a thermo-mechanical interval, a thermal-only one, and the restart."""
    f = tmp_path / "spin.toml"
    f.write_text(SPIN)
    ref = simulate("blade_loss_5700", duration=0.3, figures=False)
    spin = simulate(str(f), duration=0.3, figures=False)
    assert [i["phase"] for i in spin.summary["timeline"]] == [i["phase"] for i in ref.summary["timeline"]]
    assert len(ref.signals) > 10
    for ref_name in ref.signals:
        assert np.array_equal(spin[ref_name], ref[ref_name]), ref_name
