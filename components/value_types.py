"""The value types a port or parameter can have, and the checks of a value against its declaration.

A variable's ``type`` is one of the contract's kinds; ``fmi_type`` keeps the FMI 1.0 / 2.0 / 3.0 type it came from
(an imported FMU's ``Float32``, ``Int8``, ``UInt64``, ``Enumeration``...), which fixes its range:

=========  ==========================================================  =========================
kind       FMI 2.0 / FMI 3.0 types                                     carried by the master as
=========  ==========================================================  =========================
Real       Real / Float64, Float32                                     float64 arrays
Integer    Integer, Enumeration / Int8..Int64, UInt8..UInt64,          int64 arrays (UInt64: uint64)
           Enumeration
Boolean    Boolean / Boolean                                           bool arrays
String     String / String                                             object arrays of str
Binary     - / Binary                                                  not carried (see below)
Clock      - / Clock                                                   not carried
=========  ==========================================================  =========================

Binary and Clock ports are declared (so that a connection to one is refused by name) but hold no value: an FMU
with such a port works as long as the port is left unconnected (it keeps the FMU's own start value).

Values are checked, never coerced silently: an Integer takes whole numbers only (7.9 is an error, not 7), a
Boolean takes true/false or exactly 0/1 (2 is an error, not true), numbers must lie in the declared
``[min, max]`` and in the range of the FMI type, an Enumeration takes one of its items' values.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from .errors import ContractError

KINDS = ("Real", "Integer", "Boolean", "String", "Binary", "Clock")
#: kinds whose values the master does not carry (ports of these kinds may only stay unconnected)
UNCARRIED = ("Binary", "Clock")

#: value range of every integer FMI type (FMI 2.0 ``Integer`` is a 32-bit int)
INTEGER_RANGES = {
    "Int8": (-2**7, 2**7 - 1), "UInt8": (0, 2**8 - 1), "Int16": (-2**15, 2**15 - 1), "UInt16": (0, 2**16 - 1),
    "Int32": (-2**31, 2**31 - 1), "UInt32": (0, 2**32 - 1), "Int64": (-2**63, 2**63 - 1), "UInt64": (0, 2**64 - 1),
    "Integer": (-2**31, 2**31 - 1),
}
#: FMI type -> kind
KIND_OF = {"Real": "Real", "Float64": "Real", "Float32": "Real", "Boolean": "Boolean", "String": "String",
           "Binary": "Binary", "Clock": "Clock", "Enumeration": "Integer",
           **{t: "Integer" for t in INTEGER_RANGES}}
#: largest integer magnitude below which every integer is exact in a float64
EXACT_IN_DOUBLE = 2**53


def dtype_of(kind: str, fmi_type: str = "") -> Any:
    if kind == "Real":
        return np.float64
    if kind == "Integer":
        return np.uint64 if fmi_type == "UInt64" else np.int64
    if kind == "Boolean":
        return np.bool_
    return object


def integer_range(var) -> tuple[int, int]:
    """The range of an Integer variable: its declared min/max within its FMI type's range (int64 natively)."""
    lo, hi = INTEGER_RANGES.get(var.fmi_type, INTEGER_RANGES["Int64"])
    if var.min is not None:
        lo = max(lo, math.ceil(var.min))
    if var.max is not None:
        hi = min(hi, math.floor(var.max))
    return lo, hi


def _flat(value: Any) -> list:
    if isinstance(value, np.ndarray):
        return value.reshape(-1).tolist()
    if isinstance(value, (list, tuple)):
        out = []
        for v in value:
            out.extend(_flat(v))
        return out
    return [value]


def check_value(var, value: Any, where: str) -> np.ndarray:
    """``value`` as an array of ``var.size`` values of ``var``'s kind, or a ContractError naming ``where``.

    Used for parameters, constant inputs and start values alike (never in the stepping loop)."""
    kind = var.type
    if kind in UNCARRIED:
        raise ContractError(f"{where}: a {var.fmi_type or kind} variable cannot be given a value here "
                            "(rotorcosim does not carry binary or clock values)")
    items = _flat(value)
    if len(items) != var.size:
        raise ContractError(f"{where}: expected {var.size} value(s), got {len(items)}")
    if kind == "String":
        if not all(isinstance(x, str) for x in items):
            raise ContractError(f"{where}: expected a string, got {value!r}")
        return np.array(items, dtype=object)
    out = []
    for x in items:
        if isinstance(x, np.generic):
            x = x.item()
        if kind == "Boolean":
            if isinstance(x, bool):
                out.append(x)
            elif isinstance(x, (int, float)) and x in (0, 1):
                out.append(bool(x))
            else:
                raise ContractError(f"{where}: expected a Boolean (true/false, or 0/1), got {x!r}")
            continue
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            raise ContractError(f"{where}: expected a number ({var.fmi_type or kind}), got {x!r}")
        if isinstance(x, float) and not math.isfinite(x):
            raise ContractError(f"{where}: value is not finite ({x!r})")
        if kind == "Integer":
            if isinstance(x, float) and x != math.floor(x):
                raise ContractError(f"{where}: expected an integer ({var.fmi_type or 'Integer'}), got {x!r}")
            x = int(x)
            lo, hi = integer_range(var)
            if not lo <= x <= hi:
                raise ContractError(f"{where}: {x} is outside the range [{lo}, {hi}] of {var.fmi_type or 'Integer'}"
                                    + (" (declared min/max)" if var.min is not None or var.max is not None else ""))
            if var.choices and x not in var.choices:
                raise ContractError(f"{where}: {x} is not a value of the enumeration (its values: "
                                    f"{', '.join(map(str, var.choices))})")
        else:
            x = float(x)
            if var.fmi_type == "Float32" and abs(x) > float(np.finfo(np.float32).max):
                raise ContractError(f"{where}: {x!r} is outside the range of Float32")
            if (var.min is not None and x < var.min) or (var.max is not None and x > var.max):
                lo = "-inf" if var.min is None else f"{var.min:g}"
                hi = "inf" if var.max is None else f"{var.max:g}"
                raise ContractError(f"{where}: {x!r} is outside the declared range [{lo}, {hi}]"
                                    + (f" [{var.unit}]" if var.unit not in ("", "1") else ""))
        out.append(x)
    return np.array(out, dtype=dtype_of(kind, var.fmi_type))
