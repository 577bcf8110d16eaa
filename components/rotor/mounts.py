"""The engine's mounts to an airframe: the ``[airframe]`` and ``[mount.NAME]`` tables of an engine file.

A mount NAME ties springs on the engine's structure to one interface point of the airframe's reduced model (the
file ``[airframe] model``, docs/reference/airframe-format.md). Spring s acts along the axis ``dir`` (0, 1, 2: the
translations x, y, z; 3, 4, 5: the rotations about x, y, z, on a spool node only) between the engine's DOF
u_e,s at its ``node`` and the interface point's DOF u_a,s along the same axis; the force it carries into the
airframe is

    f_s = k_s (u_e,s - u_a,s) + c_s (v_e,s - v_a,s),

and -f_s acts on the engine. A translation spring may end off the interface point (``offset_mm``: its end r_s
from the point, in the engine's axes): its end is then rigidly tied to the point, u_a,s = e_s . (u_I + theta_I x r_s)
(u_I, theta_I the point's translations and rotations: its shape must give rotations), and the point carries its
force and the moment r_s x f_s e_s. The engine model (model.py) holds the part ``-k_s u_e,s - c_s v_e,s`` as a spring
and damper to ground at the engine DOF, exactly as a casing mount to ground: an engine whose airframe does not
move is the engine on rigid mounts. The rest, ``k_s u_a,s + c_s v_a,s``, is the force the airframe's motion puts
on the engine through the mount: the airframe component computes it (components/airframe) and the rotor takes it
at its input ``F_mount_NAME`` (one value per spring). The mount's interface load is the sum of its springs'
f_s along their axes (a force x y z) and, when a spring acts on a rotation or ends off the point, the moment
about the point (x y z: the rotation springs' f_s plus r_s x f_s e_s of the offset ones). A spring without an
offset ends at the point itself, so a moment of where it sits on the engine is carried only if given.

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
      { node = ["casing", 0, 0], dir = 1, k = 9.754e7, c = 1.0e4, offset_mm = [300, -300, 0] },
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
    N m s/rad], and where it ends from the interface point [m] (None: at the point)."""

    node: tuple
    dir: int
    k: float
    c: float
    offset: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class Mount:
    """A mount: its name, the airframe interface point its springs end at, the springs."""

    name: str
    interface: str
    springs: tuple[Spring, ...]

    @property
    def rotations(self) -> bool:
        """True when a spring acts on a rotation."""
        return any(s.dir >= 3 for s in self.springs)

    @property
    def moment(self) -> bool:
        """True when the mount carries a moment into the airframe: a spring acts on a rotation or ends off the
        interface point."""
        return self.rotations or any(s.offset is not None for s in self.springs)


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
    if not table and isinstance(table, (dict, type(None))) and "airframe" in data:
        # the airframe would be read and then left out: the engine ran on its ground, without a word
        raise ValueError("[airframe]: no [mount.NAME] table hangs the engine from it (each: interface = a point "
                         "of the airframe model, springs = [{node, dir, k, c}, ...]); add them, or remove [airframe]")
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
        parsed = tuple(_spring(f"{w} springs[{i}]", s, data) for i, s in enumerate(springs))
        seen: dict[tuple, int] = {}
        for i, sp in enumerate(parsed):
            at = (sp.node, sp.dir, sp.offset)
            if at in seen:
                # two springs at one point and direction add up: most often a spring copied twice
                raise ValueError(f"{w} springs[{i}]: the same node, dir and offset as springs[{seen[at]}] (two "
                                 "springs there act as one of their summed k and c: give that one)")
            seen[at] = i
        out[name] = Mount(name, m["interface"], parsed)
    return out


def _spring(w: str, s, data: dict) -> Spring:
    if not isinstance(s, dict):
        raise ValueError(f"{w}: must be a table {{node, dir, k, c}}, got {s!r}")
    unknown = sorted(set(s) - {"node", "dir", "k", "c", "offset_mm"})
    if unknown:
        raise ValueError(f"{w} {unknown[0]}: unknown key (known: node, dir, k, c, offset_mm)")
    node = s.get("node")
    if not (isinstance(node, list) and len(node) in (2, 3) and isinstance(node[0], str)):
        raise ValueError(f'{w}.node: must be ["casing", ring, circ], [spool, node] or ["hub", name], got {node!r}')
    d = s.get("dir")
    if isinstance(d, bool) or d not in range(6):
        raise ValueError(f"{w}.dir: must be 0-5 (x, y, z, rotation about x, y, z), got {d!r}")
    if "k" not in s:
        raise ValueError(f"{w}: k missing (the spring's stiffness, N/m or N m/rad)")
    offset = s.get("offset_mm")
    if offset is not None:
        if not (isinstance(offset, list) and len(offset) == 3 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in offset)):
            raise ValueError(f"{w}.offset_mm: must be three finite numbers (x y z, mm), got {offset!r}")
        if int(d) >= 3:
            raise ValueError(f"{w}.offset_mm: a rotation spring (dir {d}) turns the point the same wherever it ends: "
                             "give offset_mm on translation springs (dir 0-2) only")
        offset = tuple(1e-3 * float(v) for v in offset)
    return Spring(tuple(node), int(d), _number(f"{w}.k", s["k"], data, True),
                  _number(f"{w}.c", s.get("c", 0.0), data, False), offset)


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
