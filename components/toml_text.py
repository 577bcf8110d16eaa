"""TOML as users write it: the one parser of the text of scenario files, rotor model files and ``--set`` values.

``tomllib`` alone fails two ways on text a user may give: a leading UTF-8 byte-order mark (Windows editors
write one) was "Invalid statement (at line 1, column 1)", and arrays or inline tables nested a thousand deep
were an unexpected RecursionError, a traceback's worth of parser frames. Here the mark is dropped (it is not
content) and the nesting is a :class:`tomllib.TOMLDecodeError` like any other syntax error, so every caller's
existing handling of bad TOML names the file.
"""
from __future__ import annotations

import sys

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

BOM = "\ufeff"


def loads(text: str) -> dict:
    """``tomllib.loads(text)`` without a leading byte-order mark; too deep a nesting is a TOMLDecodeError."""
    try:
        return tomllib.loads(text.removeprefix(BOM))
    except RecursionError:
        raise tomllib.TOMLDecodeError("arrays or tables nested too deeply to be read") from None
