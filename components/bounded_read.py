"""The one way the project reads what it is given: files and archive entries with a cap on their size, and
archives with a cap on their entries, each refusal naming the limit it met.

Whatever a user points the program at (a scenario, a SPEC, an engine file, a targets table, an FMU or SSP archive,
a folder of an earlier run), reading it costs at most the cap, in memory and time, before it is refused: a file is
measured before it is read and read no further than its cap (it may grow, or be a device that never ends), and an
archive entry is measured in the archive's directory and read in chunks no further than its cap (the directory
may lie). A refusal is a :class:`TooLarge` (a ValueError: a mistake in the input, exit status 2) of one line
naming the file, the size met and the limit.

The caps lie far above anything the project reads legitimately (measured: the shipped scenario files 0.4-7 kB,
the shipped engine file 5 kB, the paper study's SPECs 2 kB and its targets 6 kB, a run's summary.json 9-28 kB, an
exported FMU's modelDescription.xml 21 kB) and low enough that a refusal costs little (an FMU declaring a 2 GiB
modelDescription.xml: refused in 3-5 s at ~60 MB of memory, tests/reliability/test_bounded_read.py):

>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "big.toml"
>>> _ = p.write_text("x = 1\\n" * 10)
>>> try:
...     read_text(p, "scenario file", limit=16)
... except TooLarge as exc:
...     print(str(exc).split(": ", 1)[1])
60 bytes, above the limit of 16 bytes a scenario file may have here
"""
from __future__ import annotations

import os
import zipfile
from pathlib import Path

MiB = 1024 ** 2
#: a text input parsed whole (TOML, JSON, CSV): scenario, SPEC, engine and ROSS files, targets, summaries
MAX_TEXT_BYTES = 16 * MiB
#: a study's table of finished runs (samples.csv, evaluations.csv), read back on resume
MAX_TABLE_BYTES = 64 * MiB
#: a run's checkpoint, read back on --resume
MAX_CHECKPOINT_BYTES = 256 * MiB
#: a dataset of a run's time series read back whole (a 2-minute monolithic run records ~1.2 million rows, ~0.5 GB
#: over all its datasets, the largest ~90 MB): a file made to declare more is refused before the read
MAX_DATASET_BYTES = 1024 * MiB
#: an archive entry read into memory (an FMU's modelDescription.xml, an SSP's SystemStructure.ssd)
MAX_ENTRY_BYTES = 64 * MiB
#: entries an archive may hold, and bytes it may extract in all (a zip bomb must not fill the disk): our FMUs
#: hold 24-32 entries and extract to under 1 MB each (measured), an SSP of many FMUs and other tools' FMUs more
MAX_ENTRIES = 20_000
MAX_EXTRACT_BYTES = 512 * MiB
#: files one scenario may read through its ``extends`` chain, and ids one template may be instantiated for (a
#: scenario of 16 MiB listing millions of ids would build millions of components before any check)
MAX_EXTENDS = 64
MAX_TEMPLATE_IDS = 1000
#: what a read asks of the operating system at a time
CHUNK = 1 * MiB


class TooLarge(ValueError):
    """An input beyond a cap of this module: one line naming it, its size and the limit."""


def size_text(n: int) -> str:
    """A byte count as it reads best: ``size_text(16 * MiB) == '16 MiB'``."""
    if n >= MiB and n % MiB == 0:
        return f"{n // MiB} MiB"
    if n >= MiB:
        return f"{n} bytes ({n / MiB:.1f} MiB)"
    return f"{n} bytes"


def _refuse(where: str, size: str, limit: int, what: str) -> TooLarge:
    article = "an" if what[:1].lower() in "aeiou" else "a"
    return TooLarge(f"{where}: {size}, above the limit of {size_text(limit)} {article} {what} may have here")


def check_size(size: int, where: str, what: str, limit: int) -> None:
    """Refuse ``size`` bytes of ``what`` at ``where`` beyond ``limit``, for a reader that knows the size before
    it reads (an HDF5 dataset's shape)."""
    if size > limit:
        raise _refuse(where, size_text(int(size)), limit, what)


def read_bytes(path: str | os.PathLike, what: str, limit: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of the file ``path`` (``what`` names it in a refusal: "scenario file"), at most ``limit``."""
    path = Path(path)
    with open(path, "rb") as f:
        size = os.fstat(f.fileno()).st_size
        if size > limit:
            raise _refuse(f"{what} {path}", size_text(size), limit, what)
        data = f.read(limit + 1)
    if len(data) > limit:   # a file that grew, or a device: no size to trust
        raise _refuse(f"{what} {path}", f"more than {size_text(limit)}", limit, what)
    return data


def read_text(path: str | os.PathLike, what: str, limit: int = MAX_TEXT_BYTES, encoding: str = "utf-8") -> str:
    """:func:`read_bytes` decoded (a UnicodeDecodeError for bytes that are not text)."""
    return read_bytes(path, what, limit).decode(encoding)


def read_table_text(path: str | os.PathLike, what: str, limit: int = MAX_TEXT_BYTES) -> str:
    """The text of a table a user wrote (a CSV file, often saved by a spreadsheet): a leading byte-order mark
    dropped (a spreadsheet's "CSV UTF-8" writes one, which would stick to the first column's name), and bytes
    that are not UTF-8 text refused in one line naming the file (a ValueError)."""
    data = read_bytes(path, what, limit)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{what} {path}: not UTF-8 text (byte {data[exc.start]:#04x} at position {exc.start}): "
                         "save it as CSV, UTF-8") from None


def entry_size(zf: zipfile.ZipFile, name: str | zipfile.ZipInfo, source: str,
               limit: int = MAX_ENTRY_BYTES) -> zipfile.ZipInfo:
    """The entry ``name`` of ``zf`` (KeyError when absent), refused when its directory gives more than ``limit``."""
    info = name if isinstance(name, zipfile.ZipInfo) else zf.getinfo(name)
    if info.file_size > limit:
        raise _refuse(f"{source}: entry {info.filename!r}", size_text(info.file_size), limit, "archive entry")
    return info


def read_entry(zf: zipfile.ZipFile, name: str | zipfile.ZipInfo, source: str, limit: int = MAX_ENTRY_BYTES) -> bytes:
    """The bytes of the entry ``name`` of the open archive ``zf`` (``source``: the archive, for the refusal), at
    most ``limit``: the directory's size is checked first, then the bytes are counted as they are inflated."""
    info = entry_size(zf, name, source, limit)
    parts, n = [], 0
    with zf.open(info) as src:
        while True:
            chunk = src.read(min(CHUNK, limit + 1 - n))
            if not chunk:
                break
            n += len(chunk)
            if n > limit:
                raise _refuse(f"{source}: entry {info.filename!r}", f"more than {size_text(limit)}", limit,
                              "archive entry")
            parts.append(chunk)
    return b"".join(parts)


def same_entries(zf: zipfile.ZipFile, a: zipfile.ZipInfo, b: zipfile.ZipInfo) -> bool:
    """Whether two entries hold the same bytes, compared chunk by chunk (never both whole in memory)."""
    with zf.open(a) as fa, zf.open(b) as fb:
        while True:
            x, y = fa.read(CHUNK), fb.read(CHUNK)
            if x != y:
                return False
            if not x:
                return True


def check_count(zf: zipfile.ZipFile, source: str, limit: int = MAX_ENTRIES) -> list[zipfile.ZipInfo]:
    """The entries of ``zf``, refused when more than ``limit``."""
    infos = zf.infolist()
    if len(infos) > limit:
        raise TooLarge(f"{source}: {len(infos)} entries, above the limit of {limit} entries an archive may hold here")
    return infos


def read_json(path: str | os.PathLike, what: str, limit: int = MAX_TEXT_BYTES):
    """The JSON document of the file ``path`` (:func:`read_text`, then ``json.loads``: a ValueError when it is
    not JSON)."""
    import json

    return json.loads(read_text(path, what, limit))
