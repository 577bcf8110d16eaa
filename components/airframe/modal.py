"""The airframe's reduced linear model: modal data at named points, read from (and written to) a TOML file.

The format (docs/reference/airframe-format.md): ``[modes]`` the natural frequencies ``frequency_Hz`` f_j (> 0:
the elastic modes; rigid-body modes are left out), the generalised masses ``modal_mass_kg`` m_j of the shapes
given (1 for mass-normalised shapes) and the modal damping ratios ``damping_ratio`` zeta_j (a list, or one
number for all); ``[interface.NAME]`` (where the engine's mounts end) and ``[response.NAME]`` (where the
vibration is read: the flight deck, a seat track) each a ``shape``, one row per mode of the point's displacement
in that mode (T1 T2 T3 [m], or T1 T2 T3 R1 R2 R3 [m, rad]: a finite-element code's eigenvector at a grid point,
in the engine's axes) and an optional ``position_mm``. Units at the edge: Hz, kg, mm; SI inside.

With the modal coordinates q (physical displacement u = Phi q at the points), each mode obeys

    m_j (q_j'' + 2 zeta_j w_j q_j' + w_j^2 q_j) = Phi_j^T f,      w_j = 2 pi f_j,

f the forces at the points. :func:`read` scales the shapes to mass-normalised ones (Phi_j / sqrt(m_j)), so that
the model carries only w, zeta and the normalised rows. The static flexibility of the retained modes at a point,
``sum_j phi_j phi_j^T / w_j^2``, is what :func:`static_flexibility` returns (the truncated model's, below the exact
flexibility by the modes left out).

Example::

    >>> from rotorcosim.components.airframe.modal import EXAMPLE, read
    >>> m = read(EXAMPLE)
    >>> sorted(m.interface), sorted(m.response)
    (['pylon_aft', 'pylon_fwd'], ['flight_deck', 'seat_track'])
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import toml_text
from ..bounded_read import read_bytes

#: the shipped example: a regional turboprop's wing, pylon and fuselage (example.py derives it)
EXAMPLE = Path(__file__).with_name("data") / "pylon_wing.toml"
#: the format this module reads ([airframe] format)
FORMAT = 1
#: the components of a point's shape row: translations, then rotations (optional)
COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")
#: the point tables
KINDS = ("interface", "response")


@dataclass(frozen=True)
class ModalModel:
    """A reduced airframe: angular frequencies ``w`` [rad/s], damping ratios ``zeta``, and per point its
    mass-normalised shape rows (modes x 3 or 6; m/sqrt(kg), rad/sqrt(kg)) and position [m] (None: not given)."""

    name: str
    w: np.ndarray
    zeta: np.ndarray
    interface: dict[str, np.ndarray]
    response: dict[str, np.ndarray]
    positions: dict[str, np.ndarray | None]
    source: str

    @property
    def n(self) -> int:
        return len(self.w)

    def shape(self, point: str) -> np.ndarray:
        """The mass-normalised shape of an interface or response point (modes x components)."""
        return self.interface[point] if point in self.interface else self.response[point]


def _bad(where: str, what: str) -> ValueError:
    return ValueError(f"{where}: {what}")


def _numbers(where: str, v, n: int | None, per: str = "one value per mode ({n})") -> np.ndarray:
    if isinstance(v, (int, float)) and not isinstance(v, bool) and n is not None:
        v = [v] * n
    if not isinstance(v, list) or not v:
        raise _bad(where, f"must be a list of numbers, got {v!r}")
    for i, x in enumerate(v):
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
            raise _bad(f"{where}[{i}]", f"must be a finite number, got {x!r}")
    if n is not None and len(v) != n:
        raise _bad(where, f"needs {per.format(n=n)}, got {len(v)}")
    return np.asarray(v, dtype=float)


def parse(data: dict, where: str = "airframe model") -> ModalModel:
    """The model of a parsed file (module docstring); a key missing or a bad value is a ValueError naming it."""
    head = data.get("airframe")
    if not isinstance(head, dict):
        raise _bad(where, f"[airframe] missing (format = {FORMAT}, name)")
    if head.get("format") != FORMAT:
        raise _bad(where, f"[airframe] format = {head.get('format')!r}; this version reads format {FORMAT}")
    # a misspelt table or key would be read as absent (a response point lost, a name left empty)
    unknown = sorted(set(data) - {"airframe", "modes", *KINDS})
    if unknown:
        raise _bad(where, f"{unknown[0]}: unknown table (known: airframe, modes, {', '.join(KINDS)})")
    unknown = sorted(set(head) - {"format", "name", "source"})
    if unknown:
        raise _bad(where, f"airframe.{unknown[0]}: unknown key (known: format, name, source)")
    modes = data.get("modes")
    if not isinstance(modes, dict):
        raise _bad(where, "[modes] missing (frequency_Hz, modal_mass_kg, damping_ratio)")
    unknown = sorted(set(modes) - {"frequency_Hz", "modal_mass_kg", "damping_ratio"})
    if unknown:
        raise _bad(where, f"modes.{unknown[0]}: unknown key (known: frequency_Hz, modal_mass_kg, damping_ratio)")
    f = _numbers(f"{where}: modes.frequency_Hz", modes.get("frequency_Hz"), None)
    n = len(f)
    for i, x in enumerate(f):
        if not x > 0.0:
            raise _bad(f"{where}: modes.frequency_Hz[{i}]", f"must be > 0, got {float(x)!r} (the elastic modes only: a "
                                                            "rigid-body mode has no place in the file)")
    if "modal_mass_kg" not in modes:
        raise _bad(where, "modes.modal_mass_kg missing (the generalised mass of each shape; 1 for "
                          "mass-normalised shapes)")
    m = _numbers(f"{where}: modes.modal_mass_kg", modes["modal_mass_kg"], n)
    for i, x in enumerate(m):
        if not x > 0.0:
            raise _bad(f"{where}: modes.modal_mass_kg[{i}]", f"must be > 0, got {float(x)!r}")
    z = _numbers(f"{where}: modes.damping_ratio", modes.get("damping_ratio", 0.0), n)
    for i, x in enumerate(z):
        if not 0.0 <= x < 1.0:
            raise _bad(f"{where}: modes.damping_ratio[{i}]", f"must be within [0, 1), got {float(x)!r}")
    points: dict[str, dict[str, np.ndarray]] = {k: {} for k in KINDS}
    positions: dict[str, np.ndarray | None] = {}
    for kind in KINDS:
        table = data.get(kind, {})
        if not isinstance(table, dict):
            raise _bad(where, f"[{kind}] must be a table of named points ([{kind}.NAME] shape)")
        for name, pt in table.items():
            w = f"{where}: {kind}.{name}"
            if name in positions:
                raise _bad(w, "a point of that name is defined twice (interface and response names are one set)")
            if not isinstance(pt, dict) or "shape" not in pt:
                raise _bad(w, "must be a table with shape (one row per mode)")
            unknown = sorted(set(pt) - {"shape", "position_mm"})
            if unknown:
                raise _bad(f"{w}.{unknown[0]}", "unknown key (known: shape, position_mm)")
            rows = pt["shape"]
            if not isinstance(rows, list) or len(rows) != n:
                raise _bad(f"{w}.shape", f"needs one row per mode ({n}), got "
                                         f"{len(rows) if isinstance(rows, list) else repr(rows)}")
            width = len(rows[0]) if isinstance(rows[0], list) else 0
            if width not in (3, 6):
                raise _bad(f"{w}.shape[0]", "must be a row of 3 (T1 T2 T3) or 6 (T1 T2 T3 R1 R2 R3) numbers")
            phi = np.vstack([_numbers(f"{w}.shape[{j}]", r, width, "as many values as shape[0] ({n}: T1 T2 T3"
                                      + (" R1 R2 R3" if width == 6 else "") + ")") for j, r in enumerate(rows)])
            points[kind][name] = phi / np.sqrt(m)[:, None]
            pos = pt.get("position_mm")
            positions[name] = None if pos is None else _numbers(f"{w}.position_mm", pos, 3, "3 values (x y z, mm)") * 1e-3
    if not points["interface"]:
        raise _bad(where, "no [interface.NAME] point (where the engine's mounts end)")
    return ModalModel(str(head.get("name", "")), 2.0 * math.pi * f, z, points["interface"], points["response"],
                      positions, str(head.get("source", "")))


def read(path: str | Path) -> ModalModel:
    """The model of the file at ``path`` (module docstring); an unreadable file or a bad value is a ValueError
    naming the file and the key."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"airframe model file not found: {p}")
    try:
        data = toml_text.loads(read_bytes(p, "airframe model file").decode("utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ValueError(f"airframe model {p}: {exc}") from None
    return parse(data, f"airframe model {p}")


def static_flexibility(model: ModalModel, point: str) -> np.ndarray:
    """The retained modes' static flexibility at ``point``, sum_j phi_j phi_j^T / w_j^2 (components x
    components; m/N, rad/(N m))."""
    phi = model.shape(point)
    return phi.T @ (phi / model.w[:, None] ** 2)


def _row(values) -> str:
    return "[" + ", ".join(f"{v:.9g}" for v in values) + "]"


def to_toml(name: str, source: str, frequency_Hz, modal_mass_kg, damping_ratio, interface: dict,
            response: dict, positions_mm: dict | None = None, header: str = "") -> str:
    """The text of a model file (the format :func:`parse` reads) from arrays: per point a (modes x 3 or 6) shape
    in the engine's axes, as a finite-element code exports it. ``header``: comment lines put first (the model's
    source and derivation)."""
    out = [f"# {line}".rstrip() for line in header.splitlines()] if header else []
    out += ["[airframe]", f"format = {FORMAT}", f"name = {name!r}".replace("'", '"'),
            f"source = {source!r}".replace("'", '"'), "", "[modes]",
            f"frequency_Hz = {_row(frequency_Hz)}", f"modal_mass_kg = {_row(modal_mass_kg)}",
            f"damping_ratio = {_row(np.broadcast_to(damping_ratio, np.shape(frequency_Hz)))}"]
    for kind, pts in (("interface", interface), ("response", response)):
        for pname, phi in pts.items():
            out += ["", f"[{kind}.{pname}]"]
            if positions_mm and pname in positions_mm:
                out.append(f"position_mm = {_row(positions_mm[pname])}")
            out.append("shape = [")
            out += [f"  {_row(r)}," for r in np.asarray(phi)]
            out.append("]")
    return "\n".join(out) + "\n"
