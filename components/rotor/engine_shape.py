"""The TOML shape of an engine file: each known table and key of the engine format with the kind of value it
holds, checked before any value is read, so that a number where a table belongs, ``disks = 5`` or a list where a
number belongs is one line naming the key and the shape expected, not a crash further on.

:data:`SHAPE` is the format's tables and keys as data (docs/reference/engine-format.md); a key the format does not
know in one of these tables is a problem too (``spool.pt.speed_rmp: unknown key (did you mean 'speed_rpm'?)``): a
typo'd key would otherwise be read as absent and its default taken. The part tables (``[bearing.ID]``...,
``[mount.NAME]``, ``[airframe]``) have their own readers, which name their unknown keys (engine_parts.py,
mounts.py).
Kinds: ``"number"`` (an int or float, not a bool), ``"int"``, ``"str"``, ``"knob"`` (a number or the name of a
[calibration] entry), ``"node"`` (``[spool, node]`` or ``["hub", name]``), ``"end"`` (a node or ``"ground"``),
``("list", kind)``, ``("table", {key: kind})`` (known keys), ``("tables", kind)`` (a table of named entries, each
of ``kind``), ``("array", kind)`` (a list of entries, each of ``kind``), ``("number|list", kind)`` (a number, or
a list of ``kind`` for a coefficient over speed).

Example::

    from rotorcosim.components.rotor.engine_shape import shape_problems
    shape_problems({"engine": {"format": 1}, "disks": 5, "pedestal": {"h0": 3.0}})
    # ['pedestal.h0: must be a table (mass, k or kxx/kyy, c or cxx/cyy, k_axial), got the number 3.0']
"""
from __future__ import annotations

import difflib

NUMBER, INT, STR, KNOB, BOOL = "number", "int", "str", "knob", "bool"
NODE, END = "node", "end"


def _table(keys: dict, what: str = "") -> tuple:
    return ("table", keys, what)


def _coef():
    # a support coefficient: a number, or its values over the support's speed_rpm list
    return ("number|list", NUMBER)


#: a spool's per-element value: a number for every element, or one per element
PER_ELEMENT = ("number|list", NUMBER, "one per element")


#: the engine format's tables and keys and the kind of each
DISK = _table({"node": INT, "name": STR, "mass": KNOB, "Ip": NUMBER, "Id": NUMBER, "r_gyration_mm": NUMBER},
              "node, name, mass, Ip, Id")
LAYER = _table({"element": INT, "d_out_mm": NUMBER, "d_in_mm": NUMBER, "material": STR},
               "element, d_out_mm, d_in_mm, material")
SPOOL = _table({"name": STR, "speed_rpm": NUMBER, "material": STR, "z_mm": ("list", NUMBER),
                "d_out_mm": ("list", KNOB), "d_in_mm": ("list", KNOB), "drive_node": INT, "axial_node": INT,
                "disks": ("array", DISK), "layers": ("array", LAYER), "shear_effects": BOOL,
                "rotary_inertia": BOOL,
                "rayleigh": _table({"alpha": PER_ELEMENT, "beta": PER_ELEMENT}, "alpha, beta")},
               "speed_rpm, z_mm, d_out_mm, d_in_mm, drive_node, disks...")
SUPPORT = _table({"name": STR, "a": NODE, "b": END, "speed_rpm": ("list", NUMBER),
                  **{k: _coef() for k in ("k", "c", "kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx")},
                  "k_axial": NUMBER}, "name, a, b, k or kxx/kyy, c or cxx/cyy")
PEDESTAL = _table({"mass": NUMBER, "k": KNOB, "kxx": KNOB, "kyy": KNOB, "c": NUMBER, "cxx": NUMBER,
                   "cyy": NUMBER, "k_axial": KNOB}, "mass, k or kxx/kyy, c or cxx/cyy, k_axial")
STRUTS = _table({"k_r": NUMBER, "k_t": NUMBER, "k_a": NUMBER}, "k_r, k_t, k_a")
CASING = _table({"material": STR, "radius_mm": NUMBER, "thickness_mm": NUMBER, "n_circ": INT,
                 "ring_z_mm": ("list", NUMBER),
                 "mounts": ("array", _table({"ring": INT, "node": INT, "dir": INT, "k": KNOB, "c": NUMBER},
                                            "ring, node, dir, k, c")),
                 "hubs": ("tables", _table({"z_mm": NUMBER, "mass": NUMBER, "struts": STRUTS}, "z_mm, mass")),
                 "struts": STRUTS}, "radius_mm, thickness_mm, n_circ, ring_z_mm, hubs, mounts")
MATERIAL = _table({"E": NUMBER, "rho": NUMBER, "nu": NUMBER, "G": NUMBER}, "E, rho, nu or G")
SHAPE = _table({
    "engine": _table({"format": INT, "name": STR, "description": STR, "source": STR, "extends": STR},
                     "format, name"),
    "calibration": ("tables", "any"),
    "material": ("tables", MATERIAL),
    "damping": _table({"zeta": NUMBER, "f1_Hz": NUMBER, "f2_Hz": NUMBER}, "zeta, f1_Hz, f2_Hz"),
    "spool": ("tables", SPOOL),
    "support": ("array", SUPPORT),
    "pedestal": ("tables", PEDESTAL),
    "casing": CASING,
    "attach": ("attach", None),
    # judged by their own readers (engine_parts.py, mounts.py), which name their unknown keys
    **{t: "any" for t in ("bearing", "damper", "rubring", "thermal", "fuse", "unbalance", "airframe", "mount")},
})
ATTACH_ENTRY = _table({"node": NODE, "housing": STR}, "node, housing")


def _is_num(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _got(v) -> str:
    if isinstance(v, bool):
        return f"the boolean {str(v).lower()}"
    if _is_num(v):
        return f"the number {v!r}"
    if isinstance(v, str):
        return f"the string {v!r}"
    if isinstance(v, list):
        return f"a list of {len(v)}"
    if isinstance(v, dict):
        return "a table"
    return f"a {type(v).__name__}"


def _expected(kind) -> str:
    if kind == NUMBER:
        return "a number"
    if kind == INT:
        return "an integer"
    if kind == STR:
        return "a string"
    if kind == BOOL:
        return "true or false"
    if kind == KNOB:
        return "a number or the name of a [calibration] value"
    if kind == NODE:
        return 'a node [spool, node] or ["hub", name]'
    if kind == END:
        return 'a node [spool, node], ["hub", name] or "ground"'
    tag = kind[0]
    if tag == "list":
        return {NUMBER: "a list of numbers", KNOB: "a list of numbers (or [calibration] names)",
                INT: "a list of integers"}.get(kind[1], "a list")
    if tag == "number|list":
        return f"a number, or a list of numbers ({kind[2] if len(kind) > 2 else 'one per speed_rpm'})"
    if tag == "table":
        return f"a table ({kind[2]})" if kind[2] else "a table"
    if tag == "tables":
        return "a table of named tables"
    if tag == "array":
        return f"a list of tables ({kind[1][2]})"
    return "a table"


def _did_you_mean(word: str, known) -> str:
    close = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else f" (known: {', '.join(known)})"


def _check(out: list, where: str, v, kind) -> None:
    def bad():
        out.append(f"{where}: must be {_expected(kind)}, got {_got(v)}")

    if kind == "any":
        return
    if kind == NUMBER:
        if not _is_num(v):
            bad()
    elif kind == INT:
        if not (isinstance(v, int) and not isinstance(v, bool)):
            bad()
    elif kind == STR:
        if not isinstance(v, str):
            bad()
    elif kind == BOOL:
        if not isinstance(v, bool):
            bad()
    elif kind == KNOB:
        if not (_is_num(v) or isinstance(v, str)):
            bad()
    elif kind in (NODE, END):
        if kind == END and v == "ground":
            return
        if not (isinstance(v, list) and len(v) == 2 and isinstance(v[0], str)
                and (isinstance(v[1], str) if v[0] == "hub" else isinstance(v[1], int) and not isinstance(v[1], bool))):
            bad()
    elif kind[0] == "list":
        if not isinstance(v, list):
            bad()
            return
        for i, x in enumerate(v):
            _check(out, f"{where}[{i}]", x, kind[1])
    elif kind[0] == "number|list":
        if isinstance(v, list):
            for i, x in enumerate(v):
                _check(out, f"{where}[{i}]", x, kind[1])
        elif not _is_num(v):
            bad()
    elif kind[0] == "table":
        if not isinstance(v, dict):
            bad()
            return
        for k, x in v.items():
            at = f"{where}.{k}" if where else k
            if k in kind[1]:
                _check(out, at, x, kind[1][k])
            else:
                out.append(f"{at}: unknown {'table' if not where else 'key'}{_did_you_mean(k, kind[1])}")
    elif kind[0] == "tables":
        if not isinstance(v, dict):
            bad()
            return
        for name, x in v.items():
            _check(out, f"{where}.{name}", x, kind[1])
    elif kind[0] == "array":
        if not isinstance(v, list):
            bad()
            return
        for i, x in enumerate(v):
            _check(out, f"{where}[{i}]", x, kind[1])
    elif kind[0] == "attach":
        if not isinstance(v, dict):
            bad()
            return
        for k, x in v.items():
            if k == "oil_temperature_C":
                _check(out, f"{where}.{k}", x, NUMBER)
            elif k == "unbalance" or k.startswith("rubring"):
                _check(out, f"{where}.{k}", x, _table({"node": NODE}, "node"))
            elif k.startswith("bearing"):
                _check(out, f"{where}.{k}", x, ATTACH_ENTRY)


def shape_problems(data) -> list[str]:
    """One line per value of the engine description ``data`` whose TOML shape is not the format's (empty: none);
    each names the key and the shape expected."""
    out: list[str] = []
    if not isinstance(data, dict):
        return [f"the engine description must be a table, got {_got(data)}"]
    if "shaft" in data:
        # the other model format: a test rotor's, which the rotor component reads and these commands do not
        return ["shaft: a test rotor's model file ([shaft], components/rotor/shaft_model.py), not an engine file "
                "(docs/reference/engine-format.md)"]
    _check(out, "", data, SHAPE)
    return [line.removeprefix(".") for line in out]



def refuse(found: list[str], where: str) -> None:
    """A ValueError of the first of the problems ``found`` (``where``: the file, as the reader names it), saying
    how many more there are; nothing when there are none. The one message of every reader of an engine file that
    needs the whole file (the model builder, the scenario's engine binding, critical-speeds), where check-engine
    lists them all."""
    if found:
        raise ValueError(f"{where}: {found[0]}" + (f" (and {len(found) - 1} more: rotorcosim check-engine FILE)"
                                                   if len(found) > 1 else ""))
