"""The engine's mounts to an airframe: the ``[airframe]`` and ``[mount.NAME]`` tables of an engine file.

A mount NAME ties springs on the engine's structure to one interface point of the airframe's reduced model (the
file ``[airframe] model``, docs/reference/airframe-format.md). Spring s acts along the axis ``dir`` (0, 1, 2: the
translations x, y, z; 3, 4, 5: the rotations about x, y, z, on a spool node only) between the engine's DOF
u_e,s at its ``node`` and the interface point's DOF u_a,s along the same axis; the force it carries into the
airframe is

    f_s = k_s (u_e,s - u_a,s) + c_s (v_e,s - v_a,s),

and -f_s acts on the engine. The engine model (model.py) holds the part ``-k_s u_e,s - c_s v_e,s`` as a spring
and damper to ground at the engine DOF, exactly as a casing mount to ground: an engine whose airframe does not
move is the engine on rigid mounts. The rest, ``k_s u_a,s + c_s v_a,s``, is the force the airframe's motion puts
on the engine through the mount: the airframe component computes it (components/airframe) and the rotor takes it
at its input ``F_mount_NAME`` (one value per spring). The mount's interface load is the sum of its springs'
f_s along their axes (a force x y z, and a moment about x y z when a spring acts on a rotation): the springs of a
mount all end at the interface point, so that a moment of the springs' offsets from it is not carried.

A node is ``["casing", ring, circ]`` (an outer node of the casing shell: ring index into ``ring_z_mm``,
circumferential index from +x counter-clockwise), ``[spool, node]`` or ``["hub", name]``. No ``[mount]`` table:
no mount, the engine's own supports alone (a rigid ground).

Example (an engine file)::

    [airframe]
    model = "pylon_wing.toml"         # relative to the engine file

    [mount.fwd]
    interface = "pylon_fwd"           # an interface point of the airframe model
    springs = [
      { node = ["casing", 0, 2], dir = 0, k = 9.754e7, c = 1.0e4 },
      { node = ["casing", 0, 0], dir = 1, k = 9.754e7, c = 1.0e4 },
    ]
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

#: a mount's name: letters, digits and _ (it names the ports ``X_mount_NAME`` ... and the summary's entry)
NAME = re.compile(r"^[A-Za-z0-9_]+$")
#: the axes of a spring (dir): translations then rotations
AXES = ("x", "y", "z", "rx", "ry", "rz")
#: the bodies of a node reference that are not spools
CASING, HUB = "casing", "hub"


@dataclass(frozen=True)
class Spring:
    """One spring of a mount: the engine node, its axis (0-5), stiffness [N/m or N m/rad], damping [N s/m or
    N m s/rad]."""

    node: tuple
    dir: int
    k: float
    c: float


@dataclass(frozen=True)
class Mount:
    """A mount: its name, the airframe interface point its springs end at, the springs."""

    name: str
    interface: str
    springs: tuple[Spring, ...]

    @property
    def rotations(self) -> bool:
        """True when a spring acts on a rotation (the mount carries a moment)."""
        return any(s.dir >= 3 for s in self.springs)


def _number(where: str, v, data: dict, positive: bool) -> float:
    if isinstance(v, str):
        cal = data.get("calibration", {})
        if v not in cal:
            raise ValueError(f"{where}: {v!r} is not a [calibration] value")
        v = cal[v]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ValueError(f"{where}: must be a finite number, got {v!r}")
    if (v <= 0.0) if positive else (v < 0.0):
        raise ValueError(f"{where}: must be {'> 0' if positive else '>= 0'}, got {v!r}")
    return float(v)


def mounts(data: dict) -> dict[str, Mount]:
    """The mounts of an engine file's data, in file order (empty: none); a table or value of the wrong kind is a
    ValueError naming its key. Whether a node exists is the model's to say (model.py, engine_check.py)."""
    table = data.get("mount")
    if table is None:
        return {}
    if not isinstance(table, dict):
        raise ValueError("[mount]: must be a table of named mounts ([mount.NAME] interface, springs)")
    if table and "airframe" not in data:
        raise ValueError("[mount]: the mounts need an [airframe] table (model = the airframe's reduced model file)")
    out = {}
    for name, m in table.items():
        w = f"[mount.{name}]"
        if not NAME.match(name):
            raise ValueError(f"{w}: a mount's name is letters, digits or _")
        if not isinstance(m, dict):
            raise ValueError(f"{w}: must be a table (interface, springs)")
        unknown = sorted(set(m) - {"interface", "springs"})
        if unknown:
            raise ValueError(f"{w} {unknown[0]}: unknown key (known: interface, springs)")
        if not isinstance(m.get("interface"), str):
            raise ValueError(f"{w} interface: must be the name of an interface point of the airframe model, got "
                             f"{m.get('interface')!r}")
        springs = m.get("springs")
        if not isinstance(springs, list) or not springs:
            raise ValueError(f"{w} springs: must be a list of tables {{node, dir, k, c}}, got {springs!r}")
        out[name] = Mount(name, m["interface"], tuple(_spring(f"{w} springs[{i}]", s, data)
                                                      for i, s in enumerate(springs)))
    return out


def _spring(w: str, s, data: dict) -> Spring:
    if not isinstance(s, dict):
        raise ValueError(f"{w}: must be a table {{node, dir, k, c}}, got {s!r}")
    unknown = sorted(set(s) - {"node", "dir", "k", "c"})
    if unknown:
        raise ValueError(f"{w} {unknown[0]}: unknown key (known: node, dir, k, c)")
    node = s.get("node")
    if not (isinstance(node, list) and len(node) in (2, 3) and isinstance(node[0], str)):
        raise ValueError(f'{w}.node: must be ["casing", ring, circ], [spool, node] or ["hub", name], got {node!r}')
    d = s.get("dir")
    if isinstance(d, bool) or d not in range(6):
        raise ValueError(f"{w}.dir: must be 0-5 (x, y, z, rotation about x, y, z), got {d!r}")
    if "k" not in s:
        raise ValueError(f"{w}: k missing (the spring's stiffness, N/m or N m/rad)")
    return Spring(tuple(node), int(d), _number(f"{w}.k", s["k"], data, True),
                  _number(f"{w}.c", s.get("c", 0.0), data, False))


def airframe_model(data: dict, engine_file: str | Path | None) -> Path | None:
    """The path of the airframe's reduced model ``[airframe] model`` (relative to the engine file's folder), or
    None when the engine has no ``[airframe]``."""
    af = data.get("airframe")
    if af is None:
        return None
    if not isinstance(af, dict) or not isinstance(af.get("model"), str) or not af["model"]:
        raise ValueError("[airframe] model: must be the path of the airframe's reduced model file (TOML, "
                         "docs/reference/airframe-format.md)")
    unknown = sorted(set(af) - {"model"})
    if unknown:
        raise ValueError(f"[airframe] {unknown[0]}: unknown key (known: model)")
    p = Path(af["model"])
    if not p.is_absolute() and engine_file:
        p = Path(engine_file).parent / p
    return p


def port_group(name: str) -> str:
    """The rotor model's DOF group of mount ``name`` (model.FullModel.ports)."""
    return f"mount_{name}"
