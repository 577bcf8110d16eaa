"""The engine's running speeds (paper section 4: power turbine 16 000 rev/min, gas generator 15 000 rev/min,
constant): the one source of the default shaft speed of every component that needs one (rotor, bearing, rub ring,
thermal network). They are read from the rotor model's data file (components/rotor/data/engine.toml,
``speed_rpm`` of each spool), where the gyroscopic terms take them from too."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

_ENGINE = Path(__file__).with_name("rotor") / "data" / "engine.toml"
with open(_ENGINE, "rb") as _f:
    _DATA = tomllib.load(_f)

#: rev/min -> rad/s
RPM = math.pi / 30.0
PT_SPEED_RPM = float(_DATA["spool"]["pt"]["speed_rpm"])
GG_SPEED_RPM = float(_DATA["spool"]["gg"]["speed_rpm"])
#: the power-turbine and gas-generator speeds, rad/s
PT_OMEGA = PT_SPEED_RPM * RPM
GG_OMEGA = GG_SPEED_RPM * RPM
