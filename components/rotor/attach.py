"""Where the co-simulated parts attach to the rotor, and the rotor component's ports that follow from it.

An engine file's ``[attach]`` names any number of ball bearings ``bearing<ID> = {node, housing}`` and rub rings
``rubring<ID> = {node}`` (docs/reference/engine-format.md); ``ID`` is any name of letters, digits and ``_``
("0", "5", "front"). From those ids come, in a fixed order that the reduced model, the input vector of the
Newmark step and the kernel's offset tables share:

* the DOF groups (:func:`groups`): ``brg<ID>`` (x y z of the spool node at each bearing), ``housing<ID>`` (x y of
  each bearing's housing hub), ``rub<ID>`` (x y of the spool node at each rub ring), ``fuse<ID>`` (x y z of
  each fused bearing's housing) and ``fusehub<ID>`` (x y of the hub under it), ``unbalance`` (x y);
* the input ports (:func:`input_ports`): ``F_brg<ID>`` for every bearing, then per bearing ``F_sfd_housing<ID>``
  and (when it has a rub ring) ``F_rub_housing<ID>``, then ``F_rub<ID>`` for every rub ring, then per fused
  bearing ``F_fuse<ID>`` and ``F_fusehub<ID>``;
* the output ports (:func:`output_ports`): ``X_/V_brg<ID>``, ``X_/V_housing<ID>``, ``X_/V_rub<ID>``,
  ``X_/V_fuse<ID>``, ``X_/V_fusehub<ID>``.

A fused bearing (the engine file's ``[fuse.ID]``) has a housing of its own, a body that carries its damper and
rub ring, on a support fuse (components/fuse) to the hub of its ``[attach]`` entry: ``housing<ID>`` (x y) and
``fuse<ID>`` (x y z, the fuse component's node convention) are that body, ``fusehub<ID>`` the hub (the structure
side of the fuse).

For the paper's engine (bearings "0" and "5", rub rings "0" and "5") this is the order the rotor component has
always used, so its numbers are unchanged bit for bit. A rub ring's ring sits on the housing of the bearing of
the same id (a rub ring without such a bearing is refused by name).
"""
from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

from . import mounts as mount_tables

#: an attachment id: what follows "bearing" / "rubring" in an [attach] key
ID = re.compile(r"^[A-Za-z0-9_]+$")
#: [attach] keys that are not bearings or rub rings
OTHER_KEYS = ("unbalance", "oil_temperature_C")


@dataclass(frozen=True)
class Layout:
    """The ids of the attached bearings and rub rings, in [attach] order."""

    bearings: tuple[str, ...]
    rubrings: tuple[str, ...]
    #: the bearings whose housing sits on a support fuse ([fuse.ID])
    fuses: tuple[str, ...] = ()
    #: the engine's mounts to an airframe (mounts.py): (name, number of springs), in file order
    mounts: tuple[tuple[str, int], ...] = ()


#: the paper's engine (and the class-level declaration of the rotor component)
PAPER = Layout(("0", "5"), ("0", "5"))


#: the abbreviations the paper's engine's port descriptions use for its spools' names ([spool.NAME] name)
PAPER_SPOOLS = {"power turbine": "PT", "gas generator": "GG"}


@dataclass(frozen=True)
class Words:
    """What the port descriptions call the parts of an engine: ``spool``, the spool an attached part's node is
    on where ``on`` (``(entry, word)``: ``("bearing0", "rotor spool")``) does not say otherwise; ``hubs``
    (``(bearing id, word)``) what a bearing's housing is where it is not a casing hub. The defaults are the
    paper's engine's words (the class-level declaration of the rotor component)."""

    spool: str = "PT"
    on: tuple[tuple[str, str], ...] = ()
    hubs: tuple[tuple[str, str], ...] = ()
    #: the engine's first and second spools (None: it has one)
    first: str = "PT"
    second: str | None = "GG"

    def spool_of(self, entry: str) -> str:
        return dict(self.on).get(entry, self.spool)

    def hub_of(self, bearing: str) -> str:
        return dict(self.hubs).get(bearing, "casing hub")


def spool_word(data: dict, key) -> str:
    """How the port descriptions call the spool ``key`` of an engine file's data: its ``[spool.KEY] name`` (its
    key where it has none) followed by "spool", or the paper's abbreviation of that name ("PT", "GG")."""
    spool = (data.get("spool") or {}).get(key) if isinstance(data.get("spool"), dict) else None
    name = str((spool.get("name") if isinstance(spool, dict) else None) or key)
    return PAPER_SPOOLS.get(name, name if name.lower().endswith("spool") else f"{name} spool")


def words(data: dict, lay: Layout) -> Words:
    """The :class:`Words` of an engine file's ``data`` for its layout ``lay``: the paper's engine (and a file
    naming its spools as the paper does) gets the defaults; a test rotor's ``[shaft]``, "shaft"."""
    if "shaft" in data:
        return Words(spool="shaft", first="shaft", second=None)
    keys = list(data.get("spool") or {}) if isinstance(data.get("spool"), dict) else []
    attach = data.get("attach") if isinstance(data.get("attach"), dict) else {}
    pedestals = data.get("pedestal") if isinstance(data.get("pedestal"), dict) else {}
    on, hubs = [], []
    for entry in [f"bearing{b}" for b in lay.bearings] + [f"rubring{r}" for r in lay.rubrings]:
        node = attach.get(entry, {}).get("node") if isinstance(attach.get(entry), dict) else None
        if isinstance(node, list) and len(node) == 2 and isinstance(node[0], str):
            word = spool_word(data, node[0])
            if word != Words.spool:
                on.append((entry, word))
    for b in lay.bearings:
        housing = attach.get(f"bearing{b}", {}).get("housing") if isinstance(attach.get(f"bearing{b}"), dict) else None
        if isinstance(housing, str) and housing in pedestals:
            hubs.append((b, "pedestal"))
    first = spool_word(data, keys[0]) if keys else Words.first
    second = spool_word(data, keys[1]) if len(keys) > 1 else None if keys else Words.second
    return Words(on=tuple(on), hubs=tuple(hubs), first=first, second=second)


def layout(attach: dict, fuses=()) -> Layout:
    """The layout of an ``[attach]`` table and the ids of the file's ``[fuse.ID]`` tables; a key that is not an
    attachment, a rub ring without its bearing, or a fuse at a bearing [attach] does not have, is a ValueError
    naming it."""
    bearings, rubrings = [], []
    for key in attach:
        if key in OTHER_KEYS:
            continue
        m = re.match(r"^(bearing|rubring)(.*)$", key)
        if not m or not ID.match(m.group(2)):
            raise ValueError(f"rotor model: [attach] {key!r} is not an attachment point (known: bearing<ID>, "
                             f"rubring<ID> with ID of letters, digits or _, {', '.join(OTHER_KEYS)})")
        (bearings if m.group(1) == "bearing" else rubrings).append(m.group(2))
    for r in rubrings:
        if r not in bearings:
            raise ValueError(f"rotor model: [attach] rubring{r} has no bearing{r} (a rub ring's ring is on the "
                             f"housing of the bearing of the same id)")
    for f in fuses:
        if f not in bearings:
            raise ValueError(f"rotor model: [fuse.{f}] is at bearing{f}, which [attach] does not have (a fuse "
                             f"carries a bearing's housing; bearings: {', '.join(bearings) or 'none'})")
    return Layout(tuple(bearings), tuple(rubrings), tuple(fuses))


def on_spool(attach: dict, spool: str) -> Layout:
    """The bearings and rub rings of an ``[attach]`` table (:func:`layout`) whose node is on spool ``spool``
    (``node = [spool, node]``), in [attach] order: those whose drag and friction torques act on that spool."""
    lay = layout(attach)

    def on(entry: str) -> bool:
        node = attach[entry].get("node") if isinstance(attach[entry], dict) else None
        return isinstance(node, list) and len(node) == 2 and node[0] == spool

    return Layout(tuple(b for b in lay.bearings if on(f"bearing{b}")),
                  tuple(r for r in lay.rubrings if on(f"rubring{r}")))


def with_mounts(lay: Layout, data: dict) -> Layout:
    """``lay`` with the mounts of an engine file's data (mounts.py; none: ``lay`` itself)."""
    found = mount_tables.mounts(data)
    if not found:
        return lay
    return dataclasses.replace(lay, mounts=tuple((m.name, len(m.springs)) for m in found.values()))


def layout_of_ports(ports: dict) -> Layout:
    """The layout of a model's port groups (``FullModel.ports``), in their order."""
    return Layout(tuple(g[3:] for g in ports if g.startswith("brg")),
                  tuple(g[3:] for g in ports if g.startswith("rub")),
                  tuple(g[7:] for g in ports if g.startswith("fusehub")),
                  tuple((g[len("mount_"):], len(ports[g])) for g in ports if g.startswith("mount_")))


def groups(lay: Layout) -> list[tuple[str, str, str, int]]:
    """The DOF groups in the reduced basis's order: (group, [attach] entry, what: "node" | "housing", size)."""
    return ([(f"brg{b}", f"bearing{b}", "node", 3) for b in lay.bearings]
            + [(f"housing{b}", f"bearing{b}", "housing", 2) for b in lay.bearings]
            + [(f"rub{r}", f"rubring{r}", "node", 2) for r in lay.rubrings]
            + [(f"fuse{b}", f"bearing{b}", "fuse", 3) for b in lay.fuses]
            + [(f"fusehub{b}", f"bearing{b}", "fusehub", 2) for b in lay.fuses]
            + [("unbalance", "unbalance", "node", 2)]
            + [(mount_tables.port_group(m), f"mount.{m}", "mount", n) for m, n in lay.mounts])


def load_groups(lay: Layout) -> tuple[str, ...]:
    """The groups where forces enter (the augmentation vectors of the reduced basis), in order."""
    return tuple(g for g, _, _, _ in groups(lay))


def input_ports(lay: Layout, w: Words = Words()) -> list[tuple[str, str, int, str]]:
    """(input port, DOF group, size, description) in the order of the Newmark step's force vector; the
    descriptions in the engine's words ``w``."""
    out = [(f"F_brg{b}", f"brg{b}", 3, f"bearing #{b} force on the {w.spool_of(f'bearing{b}')} node (x y z)")
           for b in lay.bearings]
    for b in lay.bearings:
        out.append((f"F_sfd_housing{b}", f"housing{b}", 2, f"damper #{b} reaction on the {w.hub_of(b)} under "
                                                           f"bearing #{b}"))
        if b in lay.rubrings:
            out.append((f"F_rub_housing{b}", f"housing{b}", 2, f"rub ring #{b} reaction on the {w.hub_of(b)} "
                                                               f"under bearing #{b}"))
    out += [(f"F_rub{r}", f"rub{r}", 2, f"rub force on the {w.spool_of(f'rubring{r}')} node at rub ring #{r}")
            for r in lay.rubrings]
    for b in lay.fuses:
        out.append((f"F_fuse{b}", f"fuse{b}", 3, f"the fuse's force on bearing #{b}'s housing (x y z)"))
        out.append((f"F_fusehub{b}", f"fusehub{b}", 2, f"the fuse's force on the hub under bearing #{b}'s housing"))
    out += [(f"F_{mount_tables.port_group(m)}", mount_tables.port_group(m), n,
             f"the airframe's motion's force on the engine through each of the {n} springs of mount {m} "
             "(k u_a + c v_a along the spring's axis)") for m, n in lay.mounts]
    return out


def output_ports(lay: Layout, w: Words = Words()) -> list[tuple[str, str, str, int, str]]:
    """(DOF group, displacement port, velocity port, size, description of X and V: "{} at ...") in the order of
    the output rows; the descriptions in the engine's words ``w`` (the spool each part is on: "PT" for the
    paper's bearings, on its power turbine)."""
    return ([(f"brg{b}", f"X_brg{b}", f"V_brg{b}", 3, f"{w.spool_of(f'bearing{b}')} {{}} at bearing #{b} (x y z)")
             for b in lay.bearings]
            + [(f"housing{b}", f"X_housing{b}", f"V_housing{b}", 2, f"{w.hub_of(b)} {{}} under bearing #{b}")
               for b in lay.bearings]
            + [(f"rub{r}", f"X_rub{r}", f"V_rub{r}", 2, f"{w.spool_of(f'rubring{r}')} {{}} at rub ring #{r}")
               for r in lay.rubrings]
            + [(f"fuse{b}", f"X_fuse{b}", f"V_fuse{b}", 3, f"{{}} of bearing #{b}'s housing on its fuse (x y z)")
               for b in lay.fuses]
            + [(f"fusehub{b}", f"X_fusehub{b}", f"V_fusehub{b}", 2, f"hub {{}} under the fuse of bearing #{b}")
               for b in lay.fuses]
            + [(mount_tables.port_group(m), f"X_{mount_tables.port_group(m)}", f"V_{mount_tables.port_group(m)}",
                n, f"engine {{}} at each of the {n} springs of mount {m}, along its axis") for m, n in lay.mounts])
