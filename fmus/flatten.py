"""Vector ports <-> FMI scalar variables.

FMI 2.0 has scalars only, so a vector port ``X`` of size n crosses the boundary as ``X[1]`` .. ``X[n]``
(1-based, FMI's "structured" naming convention); a port of size 1 keeps its plain name ``X``. The importer
regroups the scalars of any FMU (ours or another tool's) back into ports with :func:`regroup`.
"""
from __future__ import annotations

import re
from typing import Iterable

_INDEXED = re.compile(r"^(?P<base>.+)\[(?P<index>[0-9]+)\]$")


class FlattenError(ValueError):
    """Scalar names that cannot be regrouped into vector ports (gaps, duplicates, mixed plain/indexed)."""


def scalar_names(name: str, size: int) -> list[str]:
    """The FMI scalar names of a port: ``[name]`` for size 1, ``name[1]..name[size]`` otherwise."""
    return [name] if size == 1 else [f"{name}[{i + 1}]" for i in range(size)]


def regroup(names: Iterable[str], where: str = "FMU") -> dict[str, list[str]]:
    """Group scalar names into ports, keeping first-appearance order: ``{port: [scalar names by index]}``.

    ``X[1]``, ``X[2]`` -> ``{"X": ["X[1]", "X[2]"]}``; a plain ``T`` -> ``{"T": ["T"]}``. Indices must run
    1..n without gaps or repeats, and a port cannot be both plain and indexed (a clear error otherwise)."""
    groups: dict[str, dict[int, str]] = {}
    plain: set[str] = set()
    for n in names:
        m = _INDEXED.match(n)
        base, index = (m["base"], int(m["index"])) if m else (n, 0)
        if base in plain or (index == 0 and base in groups):
            raise FlattenError(f"{where}: variable {base!r} appears both as a scalar and as indexed elements")
        if index == 0:
            plain.add(base)
            groups[base] = {0: n}
            continue
        slot = groups.setdefault(base, {})
        if index in slot:
            raise FlattenError(f"{where}: variable {n!r} is declared twice")
        slot[index] = n
    out = {}
    for base, slot in groups.items():
        if base in plain:
            out[base] = [slot[0]]
            continue
        indices = sorted(slot)
        if indices != list(range(1, len(indices) + 1)):
            raise FlattenError(f"{where}: the elements of {base!r} are not numbered 1..n without gaps "
                               f"(found indices {indices})")
        out[base] = [slot[i] for i in indices]
    return out
