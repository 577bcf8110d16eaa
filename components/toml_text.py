"""TOML as users write it: the one parser of the text of scenario files, rotor model files and ``--set`` values.

``tomllib`` alone fails two ways on text a user may give: a leading UTF-8 byte-order mark (Windows editors
write one) was "Invalid statement (at line 1, column 1)", and arrays or inline tables nested a thousand deep
were an unexpected RecursionError, a traceback's worth of parser frames; and an integer of 400 digits, which
tomllib returns as a Python int, overflowed every check that compares it as a float (an unexpected
OverflowError). Here the mark is dropped (it is not content), and the nesting and an integer beyond 64 bits
(TOML 1.0: "Arbitrary 64-bit signed integers should be accepted"; FMI's largest, UInt64, is kept too) are a
:class:`tomllib.TOMLDecodeError` like any other syntax error, so every caller's handling of bad TOML names the
file.
"""
from __future__ import annotations

import sys

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

BOM = "\ufeff"
#: the integers a value may hold: Int64 and UInt64 (FMI's widest), the range of TOML's 64-bit integers and more
INT_MIN, INT_MAX = -(2 ** 63), 2 ** 64 - 1
BEYOND_64_BITS = "is beyond 64 bits"


def loads(text: str) -> dict:
    """``tomllib.loads(text)`` without a leading byte-order mark; too deep a nesting, or an integer beyond 64 bits,
    is a TOMLDecodeError."""
    try:
        data = tomllib.loads(text.removeprefix(BOM))
    except RecursionError:
        raise tomllib.TOMLDecodeError("arrays or tables nested too deeply to be read") from None
    stack = [data]
    while stack:   # not recursive: the parser allows more nesting than a recursive walk would
        node = stack.pop()
        for v in (node.values() if isinstance(node, dict) else node):
            if isinstance(v, (dict, list)):
                stack.append(v)
            elif isinstance(v, int) and not isinstance(v, bool) and not INT_MIN <= v <= INT_MAX:
                shown = f"{str(v)[:12]}... ({len(str(abs(v)))} digits)"
                raise tomllib.TOMLDecodeError(f"the integer {shown} {BEYOND_64_BITS}: write a real number (1e400) "
                                              "if a real is meant")
    return data
