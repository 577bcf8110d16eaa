"""An engine description (a dict of the engine format) written as TOML text: floats with ``repr`` (they read
back bit for bit), lists of tables as ``[[...]]`` at the top level and inline tables inside a table.

Example: ``write(engine, "engine.toml")``; ``dumps(engine)`` returns the text.
"""
from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path


def _key(k: str) -> str:
    return k if k.replace("_", "").replace("-", "").isalnum() else '"' + k.replace('"', '\\"') + '"'


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"engine description: {v!r} cannot be written (not a finite number)")
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if hasattr(v, "item"):        # numpy scalar
        return _value(v.item())
    raise TypeError(f"engine description: cannot write a {type(v).__name__} as TOML")


def _table(lines: list, name: str, table: dict) -> None:
    scalars = {k: v for k, v in table.items() if not isinstance(v, dict)}
    subs = {k: v for k, v in table.items() if isinstance(v, dict)}
    if scalars or not subs:
        lines.append(f"[{name}]")
        for k, v in scalars.items():
            if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                lines.append(f"{_key(k)} = [")
                lines.extend(f"  {_value(x)}," for x in v)
                lines.append("]")
            else:
                lines.append(f"{_key(k)} = {_value(v)}")
        lines.append("")
    for k, v in subs.items():
        _table(lines, f"{name}.{_key(k)}", v)


def dumps(engine: dict, header: str = "") -> str:
    """The TOML text of ``engine`` (``header``: comment lines put first)."""
    lines = [f"# {h}" if h else "#" for h in header.splitlines()]
    if lines:
        lines.append("")
    for k, v in engine.items():
        if not isinstance(v, (dict, list)) or (isinstance(v, list) and not all(isinstance(x, dict) for x in v)):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in engine.items():
        if isinstance(v, dict):
            _table(lines, _key(k), v)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for item in v:
                lines.append(f"[[{_key(k)}]]")
                lines.extend(f"{_key(a)} = {_value(b)}" for a, b in item.items())
                lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def refuse_invalid(engine: dict, path) -> None:
    """A ValueError with the first problem ``rotorcosim check-engine`` would find in ``engine`` (the same checks:
    :func:`rotorcosim.components.rotor.engine_check.problems`), naming the element and the key, if any."""
    from rotorcosim.components.rotor.engine_check import problems

    found = problems(engine)
    if found:
        more = f" (and {len(found) - 1} more)" if len(found) > 1 else ""
        raise ValueError(f"{path}: not written, check-engine would reject it: {found[0]}{more}")


def write(engine: dict, path, header: str = "") -> None:
    """Write ``engine`` to ``path`` whole or not at all (a temporary file renamed into place); an engine that
    ``check-engine`` would reject is refused (:func:`refuse_invalid`) and nothing is written."""
    refuse_invalid(engine, path)
    text = dumps(engine, header)
    p = Path(path)
    fd, tmp = tempfile.mkstemp(dir=p.parent if str(p.parent) else ".", prefix=f".{p.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
