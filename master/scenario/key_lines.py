"""Where a key is written in a scenario file, for an error's ``file:line``: TOML parsers do not keep value
positions, so the line is searched for (best effort), in the file and in the files it extends."""
from __future__ import annotations

import os
import re
from pathlib import Path

_HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")


def locate(source: Path | None, table: str, key: str | None) -> int | None:
    """The 1-based line of ``source`` where ``key`` is written in ``table`` (best effort), or None."""
    if source is None:
        return None
    try:
        lines = Path(source).read_text().splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    head = re.split(r"[ .]", table)[0]
    wanted = re.compile(r"(^|[{,\s])[\"']?" + re.escape(key) + r"[\"']?\s*=") if key else None
    current = ""
    fallback = None
    for i, line in enumerate(lines, 1):
        m = _HEADER.match(line)
        if m:
            current = m.group(1).replace('"', "").replace("'", "")
            if wanted is None and current == table:
                return i
            continue
        if wanted is None or not wanted.search(line.split("#")[0]):
            continue
        if current == table or (current == "" and table == head):
            return i
        if fallback is None and (current.startswith(head) or current == ""):
            fallback = i
    return fallback


_EXTENDS = re.compile(r"^\s*extends\s*=\s*(\[[^\]]*\]|\"[^\"]*\"|'[^']*')", re.M)


def locate_in_bases(source: Path | None, table: str, key: str, seen=()) -> tuple[Path | None, int | None]:
    """(file, line) of ``key`` in the scenarios ``source`` extends (their text's ``extends = ...``), or Nones."""
    if source is None or source in seen or len(seen) > 20:
        return None, None
    try:
        text = Path(source).read_text()
    except (OSError, UnicodeDecodeError):
        return None, None
    for m in _EXTENDS.finditer(text):
        for name in re.findall(r"[\"']([^\"']+)[\"']", m.group(1)):
            base = Path(os.path.realpath(Path(source).parent / name))
            line = locate(base, table, key)
            if line:
                return base, line
            found = locate_in_bases(base, table, key, seen + (source,))
            if found[1]:
                return found
    return None, None
