"""A flight profile: a table of time against flight condition, read from a CSV file, as Mach number and the
inlet's total temperature and pressure ratios (``theta``, ``delta``: atmosphere.py) at each row.

The file: ``#`` comment lines (the profile's reasoning belongs there), then a header naming the columns, then one
row per point, comma-separated. The accepted columns:

* ``time_s``: the run's time [s], strictly increasing (always);
* the flight condition, one of two forms:
  - ``altitude_m`` or ``altitude_ft`` (ISA geopotential altitude, -500 to 20 000 m) and ``mach`` (0 <= M < 1);
  - ``airspeed_m_s`` (true airspeed, >= 0) and ``density_kg_m3`` (> 0, within the ISA's range from -500 to
    20 000 m): the air at the ISA's temperature at that density's altitude (atmosphere.density_altitude), the
    Mach number the airspeed over its speed of sound.

Between rows the spool interpolates the law's values linearly in time; before the first row and after the last it
holds them. Example (docs/examples/diversion/diversion_180min.csv is a shipped one)::

    # cruise, then an approach
    time_s, altitude_ft, mach
    0, 35000, 0.80
    600, 1500, 0.25
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..bounded_read import read_table_text
from .atmosphere import H_BOTTOM, H_TOP, density_altitude, isa, speed_of_sound, total_ratios

FlightProfile = namedtuple("FlightProfile", "t mach theta delta")
#: metres per foot (the international foot)
FOOT = 0.3048
#: the accepted column sets, after time_s
FORMS = (("altitude_m", "mach"), ("altitude_ft", "mach"), ("airspeed_m_s", "density_kg_m3"))
#: the Mach number the windmilling correlation and the subsonic inlet stop at
MACH_MAX = 1.0


def read_profile(path: str) -> FlightProfile:
    """The profile of the CSV file ``path`` (module docstring); a one-line ValueError naming the file, the line
    and the column of a fault."""
    text = read_table_text(path, "flight profile")
    rows, header = [], None
    for no, line in enumerate(text.splitlines(), 1):
        body = line.split("#", 1)[0].strip()
        if not body:
            continue
        cells = [c.strip() for c in body.split(",")]
        if header is None:
            header = (no, cells)
            continue
        if len(cells) != len(header[1]):
            raise ValueError(f"{path}: line {no}: {len(cells)} values for the {len(header[1])} columns "
                             f"{', '.join(header[1])}")
        try:
            vals = [float(c) for c in cells]
        except ValueError:
            raise ValueError(f"{path}: line {no}: {body!r} is not a row of numbers") from None
        bad = [name for name, v in zip(header[1], vals) if not math.isfinite(v)]
        if bad:
            raise ValueError(f"{path}: line {no}: non-finite {bad[0]}")
        rows.append((no, vals))
    if header is None or not rows:
        raise ValueError(f"{path}: no rows (a header, e.g. \"time_s, altitude_ft, mach\", then one row per point)")
    names = header[1]
    form = next((f for f in FORMS if sorted(names) == sorted(("time_s", *f))), None)
    if form is None:
        raise ValueError(f"{path}: line {header[0]}: columns {', '.join(names)}; accepted: time_s with "
                         + " | ".join(" and ".join(f) for f in FORMS))
    lines = [no for no, _ in rows]
    col = {name: np.array([v[i] for _, v in rows]) for i, name in enumerate(names)}
    t = col["time_s"]
    back = np.flatnonzero(np.diff(t) <= 0.0)
    if back.size:
        i = int(back[0]) + 1
        raise ValueError(f"{path}: line {lines[i]}: time_s = {t[i]:g} s does not increase (the row before: "
                         f"{t[i - 1]:g} s); the times must increase strictly")

    def check(name, ok, need):
        wrong = np.flatnonzero(~ok)
        if wrong.size:
            i = int(wrong[0])
            raise ValueError(f"{path}: line {lines[i]}: {name} = {col[name][i]:g}, must be {need}")

    if form[1] == "mach":
        h = col[form[0]] * (FOOT if form[0] == "altitude_ft" else 1.0)
        lo, hi = (H_BOTTOM, H_TOP) if form[0] == "altitude_m" else (H_BOTTOM / FOOT, H_TOP / FOOT)
        check(form[0], (h >= H_BOTTOM) & (h <= H_TOP), f"within the ISA's {lo:.6g} .. {hi:.6g}")
        mach = col["mach"]
        check("mach", (mach >= 0.0) & (mach < MACH_MAX), f">= 0 and < {MACH_MAX:g} (subsonic flight)")
        T, p, _ = isa(h)
    else:
        rho = col["density_kg_m3"]
        check("density_kg_m3", rho > 0.0, "> 0 kg/m^3")
        rho_top, rho_bottom = float(isa(H_TOP)[2]), float(isa(H_BOTTOM)[2])
        check("density_kg_m3", (rho >= rho_top) & (rho <= rho_bottom),
              f"within the ISA's {rho_top:.4g} .. {rho_bottom:.4g} kg/m^3 (-500 to 20 000 m)")
        check("airspeed_m_s", col["airspeed_m_s"] >= 0.0, ">= 0 m/s")
        T, p, _ = isa(density_altitude(rho))
        mach = col["airspeed_m_s"] / speed_of_sound(T)
        col["mach"] = mach
        check("mach", mach < MACH_MAX, f"< {MACH_MAX:g} (subsonic flight): the airspeed over the ISA's speed of "
              "sound at that density")
    theta, delta = total_ratios(T, p, mach)
    return FlightProfile(t.copy(), np.asarray(mach, dtype=float), theta, delta)
