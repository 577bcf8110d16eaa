"""The scenario schema's value checkers: each takes a value and returns None when it is good, else the error's
text (the schema adds the file, the table, the key and the line: schema.py). Numbers are never booleans nor strings
(TOML keeps them apart, so a scenario must too) and always finite."""
from __future__ import annotations

import difflib
import math
from typing import Any, Callable


def is_number(v: Any) -> bool:
    """A number, not a boolean (TOML keeps them apart, so a scenario must too)."""
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def kind_of(v: Any) -> str:
    """What ``v`` is, in words, for an error ("a string", "a table" ...)."""
    return {bool: "a boolean", str: "a string", list: "a list", dict: "a table"}.get(type(v), type(v).__name__)


def number(v: Any) -> str | None:
    """A finite number (not a boolean). Each checker returns None for a good value ``v`` and otherwise the
    error's text.

    >>> number(2.5) is None, number("2.5")
    (True, "must be a number, got a string ('2.5')")
    """
    if not is_number(v):
        return f"must be a number, got {kind_of(v)} ({v!r})"
    if not math.isfinite(v):
        return f"must be a finite number, got {v!r}"
    return None


def positive(v: Any) -> str | None:
    """A finite number > 0 (a step [s], a tolerance ...)."""
    err = number(v)
    if err is None and v <= 0:
        return f"must be a positive number, got {v!r}"
    return err


def fraction(v: Any) -> str | None:
    """A finite number in (0, 1]: a relative tolerance (0.02 is 2 %; a value above 1 accepts a change larger than
    the value itself, and is most often a percentage given as a fraction's key)."""
    err = positive(v)
    if err is None and v > 1:
        return f"is a fraction (0.02 = 2 %), at most 1, got {v!r}"
    return err


def not_negative(v: Any) -> str | None:
    """A finite number >= 0."""
    err = number(v)
    if err is None and v < 0:
        return f"must be a number >= 0, got {v!r}"
    return err


def whole_positive(v: Any) -> str | None:
    """A positive whole number, written as an integer or a float (5, 5.0, 1e12): a count of rotor cycles whose
    mean is taken. 2.5 cycles of a periodic power average to a value that depends on where the window starts."""
    err = positive(v)
    if err is None and v != int(v):
        return f"must be a whole number of rotor cycles, got {v!r}"
    return err


def count(v: Any) -> str | None:
    """An integer >= 1 (written as an integer: 3, not 3.0)."""
    if not isinstance(v, int) or isinstance(v, bool):
        return f"must be a whole number, got {kind_of(v)} ({v!r})"
    return None if v >= 1 else f"must be >= 1, got {v!r}"


def text(v: Any) -> str | None:
    """A string."""
    return None if isinstance(v, str) else f"must be a string, got {kind_of(v)} ({v!r})"


def boolean(v: Any) -> str | None:
    """true or false."""
    return None if isinstance(v, bool) else f"must be true or false, got {kind_of(v)} ({v!r})"


def one_of(*allowed: str) -> Callable[[Any], str | None]:
    """A checker of a string among ``allowed`` (its error suggests the nearest one).

    >>> one_of("jacobi", "gauss-seidel")("gauss_seidel")
    "'gauss_seidel' is not one of 'jacobi', 'gauss-seidel' (did you mean 'gauss-seidel'?)"
    """
    def check(v: Any) -> str | None:
        if not isinstance(v, str) or v not in allowed:
            return f"{v!r} is not one of {', '.join(repr(a) for a in allowed)}" + did_you_mean(v, allowed)
        return None
    return check


def port_ref(v: Any) -> str | None:
    """A port reference written ``"component.port"``."""
    if not isinstance(v, str):
        return f"must be a string 'component.port', got {kind_of(v)} ({v!r})"
    comp, dot, port = v.partition(".")
    return None if dot and comp and port else f"{v!r} must be written 'component.port'"


def list_of(item: Callable[[Any], str | None]) -> Callable[[Any], str | None]:
    """A checker of a list whose every element passes ``item`` (the error names the element, from 1)."""
    def check(v: Any) -> str | None:
        if not isinstance(v, list):
            return f"must be a list, got {kind_of(v)} ({v!r})"
        for i, x in enumerate(v):
            err = item(x)
            if err:
                return f"item {i + 1}: {err}"
        return None
    return check


def text_or_texts(v: Any) -> str | None:
    """A string or a list of strings (``extends``: one base file or several)."""
    return None if isinstance(v, str) else list_of(text)(v)


def numbers(v: Any) -> str | None:
    """A number or a non-empty list of numbers (a vector port's value)."""
    if isinstance(v, list):
        return "must not be an empty list" if not v else list_of(number)(v)
    return number(v)


def parameter_value(v: Any) -> str | None:
    """A component parameter's value: a boolean, a string, a finite number or a non-empty list of numbers (its
    unit is the parameter's own, SI)."""
    if isinstance(v, (bool, str)):
        return None
    if isinstance(v, list):
        return "must not be an empty list" if not v else list_of(number)(v)
    return number(v)


def did_you_mean(word: Any, known) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``known`` to ``word``, or an empty string."""
    if not isinstance(word, str):
        return ""
    close = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""
