"""Bearing data (the paper's Table 3 plus the stated design values in data/bearings.toml) and the derived
geometry of eqs. (6)-(9): pitch diameter, groove-centre distances l_oi, l_oe, ball mass, Hertz constants,
outer race + journal mass.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from .hertz import HertzContact, effective_modulus, race_contact

DATA_FILE = Path(__file__).with_name("data") / "bearings.toml"
with open(DATA_FILE, "rb") as _f:
    DATA = tomllib.load(_f)
BEARINGS = {int(k): v for k, v in DATA["bearing"].items()}
#: the model's speed range: bore [mm] x inner race speed [rev/min] at most this (data/bearings.toml [design])
DN_LIMIT = float(DATA["design"]["dn_limit"])


def speed_limit(bore: float) -> float:
    """The highest inner race speed [rad/s] the model is declared for, a bearing of bore ``bore`` [m]:
    n_max = DN_LIMIT / (bore in mm) rev/min (bearing 0, 50.8 mm: 49 213 rev/min; bearing 5, 83.8 mm: 29 833)."""
    return DN_LIMIT / (_positive("bore", bore) * 1e3) * math.pi / 30.0


def table3(bearing: int) -> dict:
    """Raw data of bearing 0 or 5 (as in the data file, units in the key names)."""
    if bearing not in BEARINGS:
        raise ValueError(f"unknown bearing number {bearing!r}: Table 3 has bearings {sorted(BEARINGS)}")
    return dict(BEARINGS[bearing])


@dataclass(frozen=True)
class BearingGeometry:
    """Everything the contact model needs, SI units."""

    Z: int                 # number of balls
    D: float               # ball diameter, m
    d_m: float             # pitch diameter, m
    alpha0: float          # initial (unloaded) contact angle, rad
    f_i: float             # groove curvature ratios
    f_o: float
    l_oi: float            # distance groove centre p - ball centre, no load: (f_i - 1/2) D
    l_oe: float            # distance groove centre q - ball centre, no load: (f_o - 1/2) D
    m_b: float             # ball mass, kg
    inner: HertzContact
    outer: HertzContact
    preload: float         # N (axial, Table 3)
    m_outer_race: float    # kg
    m_journal: float       # kg (the damper journal alone)

    @property
    def K_i(self) -> float:
        return self.inner.K

    @property
    def K_e(self) -> float:
        return self.outer.K

    def cage_speed(self, omega: float) -> float:
        """Cage (ball orbit) speed for inner race speed omega and a stationary outer race:
        omega_c = omega/2 (1 - D cos(alpha0) / d_m) (rolling without slip; Harris & Kotzalas)."""
        return 0.5 * omega * (1.0 - self.D * math.cos(self.alpha0) / self.d_m)

    def centrifugal_force(self, omega: float) -> float:
        """Ball centrifugal force F_c = m_b (d_m/2) omega_c^2 of eq. (4), N."""
        wc = self.cage_speed(omega)
        return self.m_b * 0.5 * self.d_m * wc * wc


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def ring_mass(d_outer: float, d_inner: float, length: float, density: float) -> float:
    return density * math.pi / 4.0 * (d_outer ** 2 - d_inner ** 2) * length


def build_geometry(bearing: int | None = None, *, Z: int | None = None, D: float | None = None,
                   d_m: float | None = None, alpha0_deg: float | None = None, f_i: float | None = None,
                   f_o: float | None = None, preload: float | None = None,
                   table: dict | None = None) -> BearingGeometry:
    """Geometry of Table 3 bearing ``bearing`` with optional overrides (any bearing if all are given); ``table``
    replaces entries of the bearing's Table 3 record (its keys and units: ``bore_mm``, ``outside_diameter_mm``,
    ``width_mm``, ``balls``, ``ball_diameter_mm``, ``contact_angle_deg``, ``preload_N``...)."""
    raw = table3(bearing) if bearing is not None else {}
    if table:
        raw.update(table)
    if raw and "bore_mm" in raw and "ball_diameter_mm" in raw:
        room = 0.5 * (raw["outside_diameter_mm"] - raw["bore_mm"])
        if not (math.isfinite(room) and room > 0):
            raise ValueError(f"the outside diameter {raw['outside_diameter_mm']:g} mm must exceed the bore "
                             f"{raw['bore_mm']:g} mm")
        D_mm = raw["ball_diameter_mm"] if D is None else D * 1e3
        if not D_mm < room:
            raise ValueError(f"a ball of {D_mm:g} mm does not fit between the races: the radial room (outside "
                             f"diameter - bore) / 2 is {room:g} mm")
    design, mat = DATA["design"], DATA["material"]

    def pick(value, key, scale=1.0):
        if value is not None:
            return value
        if key not in raw:
            raise ValueError(f"{key} not given and no Table 3 bearing selected")
        return raw[key] * scale

    Z = int(pick(Z, "balls"))
    if Z < 3:
        raise ValueError(f"number of balls must be >= 3, got {Z}")
    D = _positive("ball diameter", pick(D, "ball_diameter_mm", 1e-3))
    if d_m is None and raw:
        # mean of bore and OD (see data file)
        d_m = 0.5 * (raw["bore_mm"] + raw["outside_diameter_mm"]) * 1e-3
    d_m = _positive("pitch diameter", d_m)
    if d_m <= D:
        raise ValueError(f"pitch diameter {d_m} m must exceed the ball diameter {D} m")
    if Z * D >= math.pi * d_m:
        raise ValueError(f"{Z} balls of {D} m do not fit on a pitch circle of {d_m} m")
    alpha0 = math.radians(float(pick(alpha0_deg, "contact_angle_deg")))
    if not (0.0 <= alpha0 < 0.5 * math.pi):
        raise ValueError(f"contact angle must be in [0, 90) deg, got {math.degrees(alpha0)}")
    f_i = float(design["groove_curvature_inner"] if f_i is None else f_i)
    f_o = float(design["groove_curvature_outer"] if f_o is None else f_o)
    for name, f in (("groove_curvature_inner", f_i), ("groove_curvature_outer", f_o)):
        if not (math.isfinite(f) and 0.5 < f < 1.0):
            raise ValueError(f"{name} must be in (0.5, 1) (groove radius / ball diameter), got {f!r}")
    preload = float(pick(preload, "preload_N"))
    if not (math.isfinite(preload) and preload >= 0.0):
        raise ValueError(f"preload must be a finite number >= 0 N, got {preload!r}")
    rho, E, nu = float(mat["density"]), float(mat["elastic_modulus"]), float(mat["poisson_ratio"])
    E_eff = effective_modulus(E, nu, E, nu)
    inner = race_contact(D, d_m, alpha0, f_i, E_eff, "inner")
    outer = race_contact(D, d_m, alpha0, f_o, E_eff, "outer")
    m_b = rho * math.pi * D ** 3 / 6.0
    m_e = m_j = 0.0
    if raw:
        # Outer race: solid steel ring from the groove bottom (d_m + D) to the OD, over the width.
        OD, width = raw["outside_diameter_mm"] * 1e-3, raw["width_mm"] * 1e-3
        m_e = ring_mass(OD, d_m + D, width, rho)
        # Journal (data file, the reading of eq. 5's m_j): journal_wall_mm = 0, a solid steel sleeve from the
        # bearing OD to the damper journal radius over the damper length (Table 3; the paper's Table 1 R_j);
        # > 0, "the rings alone": a ring of that radial wall under the film land.
        d_j = 2.0 * raw["journal_radius_mm"] * 1e-3
        wall = float(design.get("journal_wall_mm", 0.0)) * 1e-3
        if not (math.isfinite(wall) and 0.0 <= wall < 0.5 * d_j - 0.5 * OD):
            raise ValueError(f"bearings.toml [design] journal_wall_mm must be 0 (solid sleeve) or a wall thinner than "
                             f"the sleeve, got {wall * 1e3!r} mm")
        m_j = ring_mass(d_j, d_j - 2.0 * wall if wall > 0.0 else OD, raw["journal_length_mm"] * 1e-3, rho)
    return BearingGeometry(Z=Z, D=D, d_m=d_m, alpha0=alpha0, f_i=f_i, f_o=f_o, l_oi=(f_i - 0.5) * D,
                           l_oe=(f_o - 0.5) * D, m_b=m_b, inner=inner, outer=outer, preload=preload,
                           m_outer_race=m_e, m_journal=m_j)
