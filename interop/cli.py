"""``rotorcosim import-ross ROTOR.toml --out ENGINE.toml``: a rotor saved by ROSS (``Rotor.save``) as an engine
file of rotorcosim's format (docs/reference/engine-format.md); no ROSS needed.

``--attach ID=NODE,...`` (e.g. ``0=NODE,5=NODE``; any number of ids of letters, digits or ``_``) makes the ROSS
bearings at those nodes the co-simulated ball bearings #ID
(their linear coefficients become the housings' pedestals), so that ``blade_loss.toml`` scenarios can run the
rotor; without it the file has the ROSS bearings as linear supports (critical speeds, check-engine, to_ross).
What each co-simulated part is (ball bearing, squeeze film damper, rub ring, thermal network: ROSS describes none of
them) comes from ``--parts FILE``: a TOML file of the engine format's part tables (``[bearing.ID]``,
``[damper.ID]``, ``[rubring.ID]``, ``[thermal.ID]``, ``[unbalance]``), checked and copied into the engine file.
``--attach`` needs it: without it, or with a file that leaves a required key of an attached part out, the import
is refused in one line naming every missing table and key (no generic value stands for a bearing's geometry),
and nothing is written.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.components.rotor.attach import ID

from .engine_toml import write
from .ross_import import DEFAULT_HUB_MASS_KG, DEFAULT_SPEED_RPM, from_ross


def _attach(text: str | None) -> dict:
    if not text:
        return {}
    out = {}
    for item in text.split(","):
        key, _, node = item.partition("=")
        key = key.strip()
        if not ID.match(key) or not node.strip().lstrip("-").isdigit():
            raise ValueError(f"--attach {text!r}: expected ID=NODE,... (bearing ids of letters, digits or _, and "
                             "the ROSS node numbers of their bearings, e.g. 0=2,5=9)")
        if f"bearing{key}" in out:
            raise ValueError(f"--attach {text!r}: bearing id {key!r} given twice")
        out[f"bearing{key}"] = int(node)
    return out


#: the engine format's part tables an import takes from --parts
PART_TABLES = ("bearing", "damper", "rubring", "thermal", "unbalance")


def _parts(path: str | None, engine: dict) -> dict:
    """The part tables of the file ``path`` (--parts), checked against the engine's [attach]; {} for None. An
    engine with co-simulated parts that the tables leave without a required key is refused, the keys named:
    ROSS describes no ball bearing, damper or rub ring, and no generic value stands for one."""
    from rotorcosim.components.rotor import engine_parts

    data = {}
    if path is not None:
        import tomllib

        p = Path(path)
        if p.is_dir():
            raise IsADirectoryError(f"--parts {path}: is a folder; give the TOML file of the parts ([bearing.ID], "
                                    "[damper.ID], ...)")
        if not p.is_file():
            raise FileNotFoundError(f"--parts {path}: no such file")
        try:
            data = tomllib.loads(p.read_text())
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise ValueError(f"--parts {path}: not valid TOML ({exc})") from None
        other = sorted(set(data) - set(PART_TABLES))
        if other:
            raise ValueError(f"--parts {path}: [{other[0]}] is not a part table (they are: "
                             f"{', '.join(PART_TABLES)})")
        bad = engine_parts.problems({**data, "attach": engine.get("attach", {})})
        if bad:
            raise ValueError(f"--parts {path}: {bad[0]}")
    lack = engine_parts.missing({**data, "attach": engine.get("attach", {})})
    if lack:
        where = f"--parts {path}" if path is not None else "--attach without --parts FILE"
        raise ValueError(f"{where}: the co-simulated parts lack {'; '.join(lack)} (ROSS describes no ball bearing, "
                         "damper or rub ring: give them in a --parts FILE of [bearing.ID], [damper.ID], "
                         "[rubring.ID] tables, docs/reference/engine-format.md)")
    return data


def import_ross(rotor_file: str, out: str, *, speed_rpm: float | None = None, coefficients_at: float | None = None,
                attach: str | None = None, unbalance_node: int | None = None,
                hub_mass_kg: float = DEFAULT_HUB_MASS_KG, parts: str | None = None) -> dict:
    """Read ``rotor_file`` (ROSS TOML), write the engine file ``out`` (not overwritten; written whole or not at
    all) with the part tables of the file ``parts`` and return the engine description."""
    o = Path(out)
    if o.exists():
        raise FileExistsError(f"--out {out}: already exists; choose a new file name")
    if o.parent != Path("") and not o.parent.is_dir():
        raise FileNotFoundError(f"--out {out}: the folder {o.parent} does not exist")
    engine = from_ross(rotor_file, speed_rpm=speed_rpm, speed_rpm_coefficients=coefficients_at,
                       attach=_attach(attach), unbalance_node=unbalance_node, hub_mass_kg=hub_mass_kg)
    engine.update(_parts(parts, engine))
    write(engine, o, header=f"Imported by rotorcosim import-ross from {Path(rotor_file).name}.\n"
                            "The engine format: docs/reference/engine-format.md. Check it: rotorcosim check-engine "
                            f"{o.name}")
    return engine


def add_arguments(parser):
    """The options of ``rotorcosim import-ross`` on ``parser``."""
    parser.add_argument("rotor", metavar="ROTOR.toml", help="a rotor file written by ROSS's Rotor.save")
    parser.add_argument("--out", required=True, metavar="ENGINE.toml", help="the engine file to write (new)")
    parser.add_argument("--speed", type=float, default=None, metavar="RPM",
                        help=f"the spools' running speed (ROSS files carry none; default {DEFAULT_SPEED_RPM:g})")
    parser.add_argument("--coefficients-at", type=float, default=None, metavar="RPM",
                        help="take speed-dependent bearing and seal coefficients at this speed (default: they are "
                             "carried as coefficient tables over speed_rpm)")
    parser.add_argument("--attach", default=None, metavar="ID=NODE,...",
                        help="the ROSS nodes of the bearings to co-simulate as ball bearings #ID (any number, e.g. "
                             "0=NODE,5=NODE for a scenario that extends the shipped blade_loss)")
    parser.add_argument("--unbalance-node", type=int, default=None, metavar="NODE",
                        help="ROSS node of the blade loss (with --attach; default: the first disk's)")
    parser.add_argument("--parts", default=None, metavar="FILE",
                        help="a TOML file of the attached parts ([bearing.ID], [damper.ID], [rubring.ID], "
                             "[thermal.ID], [unbalance]) copied into the engine file (--attach needs it: without "
                             "it, or with a required key left out, the import names every missing table and key "
                             "and writes nothing)")
    parser.add_argument("--hub-mass", type=float, default=DEFAULT_HUB_MASS_KG, metavar="KG",
                        help=f"housing mass of each co-simulated bearing (default {DEFAULT_HUB_MASS_KG:g})")


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    engine = import_ross(args.rotor, args.out, speed_rpm=args.speed, coefficients_at=args.coefficients_at,
                         attach=args.attach, unbalance_node=args.unbalance_node, hub_mass_kg=args.hub_mass,
                         parts=args.parts)
    spools = ", ".join(f"{k} ({len(v['z_mm'])} nodes, {len(v['disks'])} disks)" for k, v in engine["spool"].items())
    print(f"spools: {spools}; supports: {len(engine.get('support', []))}; pedestals: "
          f"{len(engine.get('pedestal', {}))}; attached: "
          f"{', '.join(k for k in engine.get('attach', {}) if k != 'oil_temperature_C') or 'nothing'}")
    print(f"written: {args.out}")
    return 0
