"""A rotor file written by ROSS's ``Rotor.save`` (TOML), read without ROSS: its elements as plain dicts.

The file (ROSS 2.x) holds ``ross_version`` and one table per element, named ``"<Kind>_<tag>"``: ``ShaftElement``
(L, idl, odl, idr, odr, n, material = {name, rho, E, G_s}, alpha, beta, shear_effects, rotary_inertia,
gyroscopic...), ``DiskElement`` (n, m, Id, Ip), ``BearingElement`` / ``SealElement`` (n, n_link, kxx... as lists
over ``frequency``), ``PointMass`` (n, m or mx, my). Any other kind is refused by name, as is a file of another
major version of ROSS.

Example::

    from rotorcosim.interop.ross_toml import read
    elements = read("rotor_example.toml")      # {"version", "shafts", "disks", "bearings", "point_masses"}
"""
from __future__ import annotations

import tomllib
from pathlib import Path

from rotorcosim.components import toml_text
from rotorcosim.components.bounded_read import read_text

#: the ROSS major versions whose files this reader knows
MAJOR_VERSIONS = ("2",)
#: element kinds carried; every other kind is an error naming it
KINDS = {"ShaftElement": "shafts", "DiskElement": "disks", "BearingElement": "bearings",
         "SealElement": "bearings", "PointMass": "point_masses"}


class RossFileError(ValueError):
    """A ROSS file this reader cannot take: the message names the file and the reason."""


def read(path: str | Path) -> dict:
    """The elements of the ROSS rotor file ``path``: ``{"version", "shafts", "disks", "bearings",
    "point_masses"}``, each a list of dicts with the file's keys (``kind`` added to bearings)."""
    p = Path(path)
    if p.is_dir():
        raise RossFileError(f"ROSS rotor file {p} is a folder, not a file written by ROSS's Rotor.save")
    if not p.is_file():
        raise FileNotFoundError(f"ROSS rotor file not found: {p}")
    try:
        data = toml_text.loads(read_text(p, "ROSS rotor file"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise RossFileError(f"ROSS rotor file {p}: not TOML ({exc})") from None
    version = data.get("ross_version")
    if not isinstance(version, str):
        raise RossFileError(f"ROSS rotor file {p}: no ross_version (not a file written by ROSS's Rotor.save)")
    if version.split(".")[0] not in MAJOR_VERSIONS:
        raise RossFileError(f"ROSS rotor file {p}: written by ROSS {version}; this importer reads files of ROSS "
                            f"{', '.join(v + '.x' for v in MAJOR_VERSIONS)}")
    out = {"version": version, "shafts": [], "disks": [], "bearings": [], "point_masses": []}
    for name, table in data.items():
        if name in ("ross_version", "parameters") or not isinstance(table, dict):
            continue
        kind = name.split("_", 1)[0]
        if kind not in KINDS:
            raise RossFileError(f"ROSS rotor file {p}: element {name!r} is a {kind}, which rotorcosim does not "
                                f"carry (it carries {', '.join(KINDS)})")
        out[KINDS[kind]].append({**table, "kind": kind, "tag": table.get("tag", name.split("_", 1)[-1])})
    if not out["shafts"]:
        raise RossFileError(f"ROSS rotor file {p}: no ShaftElement")
    return out
