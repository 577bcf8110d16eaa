"""SI unit strings of the contract (``"N.s/m"``, ``"Pa.s"``, ``"1/K"``, ``"m/s"``) as FMI 2.0 unit definitions.

FMI 2.0 expects every ``unit`` attribute to name a ``<Unit>`` of ``<UnitDefinitions>``, ideally with its
``<BaseUnit>`` exponents so that other tools can check and convert. The grammar is the one the components use:
factors joined by ``.`` (product) and ``/`` (everything after the first ``/`` is in the denominator), each an
SI symbol with an optional integer exponent (``m2``, ``s^-1``). A unit that does not parse is still defined,
without a BaseUnit (legal FMI, just not checkable). ``"1"`` is dimensionless: no ``unit`` attribute at all.

:func:`definition` gives a unit as FMI's BaseUnit does, ``(exponents, factor, offset)`` with
``value_in_base_units = factor * value + offset``: what a connection needs to convert between compatible units
(also the affine temperature units ``degC`` and ``degF``, which only stand alone).
"""
from __future__ import annotations

import re

# base dimensions of FMI 2.0's BaseUnit, in its attribute names
BASE = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")
# symbol -> (exponents over BASE, factor)
_SYMBOLS: dict[str, tuple[dict[str, int], float]] = {
    "kg": ({"kg": 1}, 1.0), "g": ({"kg": 1}, 1e-3), "m": ({"m": 1}, 1.0), "mm": ({"m": 1}, 1e-3),
    "s": ({"s": 1}, 1.0), "A": ({"A": 1}, 1.0), "K": ({"K": 1}, 1.0), "mol": ({"mol": 1}, 1.0),
    "cd": ({"cd": 1}, 1.0), "rad": ({"rad": 1}, 1.0),
    "N": ({"kg": 1, "m": 1, "s": -2}, 1.0), "Pa": ({"kg": 1, "m": -1, "s": -2}, 1.0),
    "J": ({"kg": 1, "m": 2, "s": -2}, 1.0), "W": ({"kg": 1, "m": 2, "s": -3}, 1.0),
    "Hz": ({"s": -1}, 1.0), "min": ({"s": 1}, 60.0), "h": ({"s": 1}, 3600.0),
    "rev": ({"rad": 1}, 6.283185307179586), "rpm": ({"rad": 1, "s": -1}, 6.283185307179586 / 60.0),
    "1": ({}, 1.0),
}
_FACTOR = re.compile(r"^(?P<sym>[A-Za-z]+|1)(?:\^?(?P<exp>-?[0-9]+))?$")


def base_units(unit: str) -> tuple[dict[str, int], float] | None:
    """``(exponents, factor)`` of ``unit`` over FMI's base units, or None when it does not parse."""
    num, slash, den = unit.partition("/")
    exps: dict[str, int] = {}
    factor = 1.0
    for part, sign in ((num, 1), (den, -1)):
        if not part and sign == -1 and not slash:
            continue
        for tok in part.replace("/", ".").split("."):
            m = _FACTOR.match(tok.strip())
            if not m or m["sym"] not in _SYMBOLS:
                return None
            e = int(m["exp"] or 1) * sign
            sym_exps, sym_factor = _SYMBOLS[m["sym"]]
            for k, v in sym_exps.items():
                exps[k] = exps.get(k, 0) + v * e
            factor *= sym_factor ** e
    return {k: v for k, v in exps.items() if v}, factor


def is_dimensionless(unit: str | None) -> bool:
    return unit in (None, "", "1")


#: affine units (FMI BaseUnit factor and offset over K); they do not combine with other symbols
_AFFINE = {"degC": ({"K": 1}, 1.0, 273.15), "degF": ({"K": 1}, 5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0)}


def definition(unit: str | None) -> tuple[dict[str, int], float, float] | None:
    """``(exponents, factor, offset)`` of a unit string, or None when it does not parse."""
    if is_dimensionless(unit):
        return {}, 1.0, 0.0
    if unit in _AFFINE:
        return _AFFINE[unit]
    parsed = base_units(unit)
    return None if parsed is None else (parsed[0], parsed[1], 0.0)
