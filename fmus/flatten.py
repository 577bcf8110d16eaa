"""Vector ports <-> FMI scalar variables.

FMI 2.0 has scalars only, so a vector port ``X`` of size n crosses the boundary as ``X[1]`` .. ``X[n]``
(1-based, FMI's "structured" naming convention); a port of size 1 keeps its plain name ``X``. The importer
regroups the scalars of any FMU (ours or another tool's, 0-based ``X[0]`` .. too) back into ports with
:func:`regroup`.
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
    1..n (FMI's structured naming) or 0..n-1 (a C or C++ tool's arrays: libcosim's own test FMUs) without gaps
    or repeats, and a port cannot be both plain and indexed (a clear error otherwise)."""
    groups: dict[str, dict[int, str]] = {}
    plain: dict[str, str] = {}
    for n in names:
        m = _INDEXED.match(n)
        if m is None:
            if n in groups:
                raise FlattenError(f"{where}: variable {n!r} appears both as a scalar and as indexed elements")
            plain[n] = n
            groups[n] = {}
            continue
        base, index = m["base"], int(m["index"])
        if base in plain:
            raise FlattenError(f"{where}: variable {base!r} appears both as a scalar and as indexed elements")
        slot = groups.setdefault(base, {})
        if index in slot:
            raise FlattenError(f"{where}: variable {n!r} is declared twice")
        slot[index] = n
    out = {}
    for base, slot in groups.items():
        if base in plain:
            out[base] = [plain[base]]
            continue
        indices = sorted(slot)
        first = indices[0]
        if first not in (0, 1) or indices != list(range(first, first + len(indices))):
            raise FlattenError(f"{where}: the elements of {base!r} are not numbered 1..n (or 0..n-1) without gaps "
                               f"(found indices {indices})")
        out[base] = [slot[i] for i in indices]
    return out
