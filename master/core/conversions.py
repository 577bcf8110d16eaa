"""What a connection does to the values it carries: the type and unit checks of a link, and its conversion.

Decided once, when the system is built (system.py); a link that needs no conversion gets none, so the stepping
loop of a native system (same kind, same unit on every link) is unchanged.

Types (kinds of components/value_types.py). A connection carries one kind; implicit only where nothing can be
lost:

* Real -> Real, String -> String, Boolean -> Boolean: as is (a Float32 input rounds to single precision, as the
  FMU would);
* Integer -> Integer: as is when every value of the output's range fits the input's (UInt8 -> Int16 yes,
  Int32 -> UInt8 no: ``convert = "clip"`` saturates into the input's range); an Enumeration input also needs
  the output's values to be its items;
* Integer -> Real: as is when every value is exact in double precision (all types but Int64/UInt64 without a
  narrower declared range; ``convert = "float"`` accepts the rounding of larger ones);
* anything else needs the connection's ``convert``: ``"round"`` (to the nearest integer, halves away from zero),
  ``"floor"``, ``"ceil"``, ``"truncate"`` for Real -> Integer; ``"nonzero"`` for Real/Integer -> Boolean (x != 0);
  ``"float"`` for Boolean/Integer -> Real (true = 1.0); ``"integer"`` for Boolean -> Integer (true = 1).
  A converted value outside the input's range stops the run with an error naming the connection.
* Binary and Clock ports cannot be connected (no value to carry); String converts to nothing.

Units (numeric links). Equal unit strings: as is. Different units of the same dimension (FMI BaseUnit exponents,
from the FMU's unit definitions or parsed from the string, fmus/units.py): converted through the base unit,
``y_in = (factor_out * y_out + offset_out - offset_in) / factor_in`` (K <-> degC, m <-> mm). Different
dimensions: an error. A port without a unit (``"1"``) connects to one with a unit only if the connection says
which unit the unit-less side is in, ``unit = "mm"`` (then converted like any other pair). Only a Real input
receives converted units (an Integer input needs the same unit on both sides).
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from rotorcosim.components.contract import ContractError
from rotorcosim.components.value_types import EXACT_IN_DOUBLE, UNCARRIED, dtype_of, integer_range
from rotorcosim.fmus.units import definition, is_dimensionless

CONVERSIONS = ("round", "floor", "ceil", "truncate", "nonzero", "float", "integer", "clip")
_ROUNDING = {"round": lambda x: np.sign(x) * np.floor(np.abs(x) + 0.5), "floor": np.floor, "ceil": np.ceil,
             "truncate": np.trunc}


class ConversionError(ContractError):
    """A connection whose types or units do not match and that says no (valid) conversion."""


def _a(word: str) -> str:
    return ("an " if word[0] in "AEIOU" else "a ") + word


def _fmt_dims(exps: dict) -> str:
    return ".".join(f"{k}{'' if v == 1 else v}" for k, v in sorted(exps.items())) or "1"


def unit_scale(out, inp, override: str | None, label: str) -> tuple[float, float] | None:
    """``(a, b)`` with ``y_in = a * y_out + b``, or None when no conversion is needed."""
    uo, ui = out.unit, inp.unit
    if override is None and uo == ui:
        return None                                    # the native case: one string compare, nothing else
    src, dst = label.split(" -> ")
    no, ni = is_dimensionless(uo), is_dimensionless(ui)
    do = out.unit_definition if out.unit_definition is not None else definition(uo)
    di = inp.unit_definition if inp.unit_definition is not None else definition(ui)
    if override is not None:
        if no == ni:
            raise ConversionError(f"{label}: 'unit' names the unit of the side without one, but "
                                  + ("both have units" if not no else "neither has a unit")
                                  + f" ([{uo}] -> [{ui}])")
        if no:
            uo, do = override, definition(override)
        else:
            ui, di = override, definition(override)
        if (do if no else di) is None:
            raise ConversionError(f"{label}: unit = {override!r} does not parse as a unit")
    elif no != ni:
        side, unit = (src, ui) if no else (dst, uo)
        raise ConversionError(f"{label}: {side} has no unit and the other side is in [{unit}]: say which unit "
                              f"{side}'s values are in with the connection's unit = \"...\" (e.g. unit = "
                              f"\"{unit}\")")
    if uo == ui and (do is None or di is None or do == di):
        return None
    if do is None or di is None:
        unknown = uo if do is None else ui
        raise ConversionError(f"{label}: units differ ([{uo}] -> [{ui}]) and [{unknown}] has no definition "
                              "to convert with")
    if do[0] != di[0]:
        raise ConversionError(f"{label}: units differ, [{uo}] ({_fmt_dims(do[0])}) -> [{ui}] ({_fmt_dims(di[0])}), "
                              "in dimension: they cannot be connected")
    a = do[1] / di[1]
    b = (do[2] - di[2]) / di[1]
    if a == 1.0 and b == 0.0:
        return None
    return a, b


def _range_guard(inp, label: str) -> Callable[[np.ndarray], np.ndarray]:
    lo, hi = integer_range(inp)
    dtype = dtype_of("Integer", inp.fmi_type)

    def guard(x: np.ndarray) -> np.ndarray:
        if np.any(x < lo) or np.any(x > hi):
            raise ContractError(f"{label}: converted value(s) {x[(x < lo) | (x > hi)]} outside the range "
                                f"[{lo}, {hi}] of the input")
        return x.astype(dtype)
    return guard


def link_conversion(out, inp, convert: str | None, unit: str | None, label: str) -> Callable | None:
    """The function a link applies to the output's values before they reach the input (None: none needed).

    ``out``/``inp``: the two ports' Variables; ``label``: ``"a.y -> b.u"`` for the messages."""
    if convert is not None and convert not in CONVERSIONS:
        raise ConversionError(f"{label}: convert {convert!r} not in {CONVERSIONS}")
    for var, end in ((out, label.split(" -> ")[0]), (inp, label.split(" -> ")[1])):
        if var.type in UNCARRIED:
            raise ConversionError(f"{label}: {end} is a {var.fmi_type or var.type} port; rotorcosim does not carry "
                                  f"{var.type} values: leave it unconnected")
    ko, ki = out.type, inp.type
    need = f"{label}: {_a(out.fmi_type or ko)} output into {_a(inp.fmi_type or ki)} input"
    if ko == "String" or ki == "String":
        if ko != ki:
            raise ConversionError(f"{need}: strings convert to nothing")
        if convert is not None:
            raise ConversionError(f"{label}: convert {convert!r} does not apply to strings")
        return None
    type_fn = None
    if ko == ki == "Real":
        if convert is not None:
            raise ConversionError(f"{label}: convert {convert!r} does not apply to a Real -> Real connection")
    elif ko == ki == "Boolean":
        if convert is not None:
            raise ConversionError(f"{label}: convert {convert!r} does not apply to a Boolean -> Boolean connection")
    elif ko == ki == "Integer":
        lo_o, hi_o = integer_range(out)
        lo_i, hi_i = integer_range(inp)
        fits = lo_i <= lo_o and hi_o <= hi_i
        if inp.choices is not None and not (out.choices is not None and set(out.choices) <= set(inp.choices)):
            fits = False
        if convert == "clip":
            dtype = dtype_of("Integer", inp.fmi_type)
            type_fn = lambda x: np.clip(x, lo_i, hi_i).astype(dtype)  # noqa: E731 - one of the conversions of the table
        elif convert is not None:
            raise ConversionError(f"{label}: convert {convert!r} does not apply to Integer -> Integer "
                                  "(only \"clip\")")
        elif not fits:
            raise ConversionError(f"{need}: the output's values [{lo_o}, {hi_o}] do not all fit the input "
                                  f"[{lo_i}, {hi_i}]" + (" and its enumeration items" if inp.choices else "")
                                  + ": add convert = \"clip\" to saturate, or connect ports of matching types")
        elif dtype_of("Integer", out.fmi_type) != dtype_of("Integer", inp.fmi_type):
            dtype = dtype_of("Integer", inp.fmi_type)
            type_fn = lambda x: x.astype(dtype)  # noqa: E731 - one of the conversions of the table
    elif ko == "Integer" and ki == "Real":
        lo, hi = integer_range(out)
        exact = max(abs(lo), abs(hi)) <= EXACT_IN_DOUBLE
        if convert not in (None, "float"):
            raise ConversionError(f"{label}: convert {convert!r} does not apply to Integer -> Real (only \"float\")")
        if not exact and convert is None:
            raise ConversionError(f"{need}: values beyond 2^53 would be rounded: add convert = \"float\" to "
                                  "accept that")
        type_fn = lambda x: x.astype(np.float64)  # noqa: E731 - one of the conversions of the table
    elif ko == "Real" and ki == "Integer":
        if convert not in _ROUNDING:
            raise ConversionError(f"{need} needs an explicit conversion: add convert = \"round\" (or \"floor\", "
                                  "\"ceil\", \"truncate\") to the connection")
        rnd, guard = _ROUNDING[convert], _range_guard(inp, label)
        if inp.choices is not None:
            choices = np.array(sorted(inp.choices))

            def type_fn(x, rnd=rnd, guard=guard):
                v = guard(rnd(x))
                if not np.all(np.isin(v, choices)):
                    raise ContractError(f"{label}: converted value(s) {v} are not items of the input's "
                                        "enumeration")
                return v
        else:
            type_fn = lambda x, rnd=rnd, guard=guard: guard(rnd(x))  # noqa: E731 - one of the conversions of the table
    elif ki == "Boolean":
        if convert != "nonzero":
            raise ConversionError(f"{need} needs an explicit conversion: add convert = \"nonzero\" (true where the "
                                  "value is not 0)")
        type_fn = lambda x: x != 0  # noqa: E731 - one of the conversions of the table
    elif ko == "Boolean" and ki == "Real":
        if convert != "float":
            raise ConversionError(f"{need} needs an explicit conversion: add convert = \"float\" (true = 1.0)")
        type_fn = lambda x: x.astype(np.float64)  # noqa: E731 - one of the conversions of the table
    elif ko == "Boolean" and ki == "Integer":
        if convert != "integer":
            raise ConversionError(f"{need} needs an explicit conversion: add convert = \"integer\" (true = 1)")
        guard = _range_guard(inp, label)
        type_fn = lambda x, guard=guard: guard(x.astype(np.int64))  # noqa: E731 - one of the conversions of the table
    else:  # pragma: no cover - every pair of carried kinds is handled above
        raise ConversionError(f"{need}: no conversion")
    scale = None
    if ko in ("Real", "Integer") and ki in ("Real", "Integer"):
        scale = unit_scale(out, inp, unit, label)
        if scale is not None and ki != "Real":
            raise ConversionError(f"{label}: units differ ([{out.unit}] -> [{inp.unit}]); only connections into a "
                                  "Real input convert units")
    elif unit is not None:
        raise ConversionError(f"{label}: 'unit' applies to numeric connections only")
    if scale is None:
        return type_fn
    a, b = scale
    if type_fn is None:
        return lambda x: x * a + b
    return lambda x: type_fn(x) * a + b


__all__ = ["CONVERSIONS", "ConversionError", "link_conversion", "unit_scale"]
