"""Extract an FMU or SSP archive without letting any entry write outside a fresh temporary folder.

Every entry is checked *before* anything is written: absolute paths (``/x``, ``C:x``, ``\\\\server``), ``..``
components (zip-slip), backslashes (not portable; can hide ``..\\``), symbolic links (a link inside the folder can
point anywhere, and a later entry written "through" it escapes), and, after normalisation, the final path must
still lie inside the folder. A bad archive raises :class:`UnsafeArchiveError` naming the entry, and the folder
is removed.

Caps (a zip bomb must not fill the disk): at most ``MAX_ENTRIES`` entries, ``MAX_TOTAL_BYTES`` extracted in all,
and no entry larger than ``RATIO_FLOOR_BYTES`` compressed more than ``MAX_RATIO`` times; sizes are checked from
the directory before anything is written and counted again while writing (a directory can lie). Malformed
archives (a bad CRC, a truncated entry, an unsupported compression, an entry both a file and a folder, a name
twice with different contents) raise :class:`ArchiveError` naming the entry. A name twice with identical bytes is
accepted and extracted once: FMU build tools write such archives (the Modelica Reference FMUs' FMI 3.0
``Roberts.fmu`` holds its ``extra/.../fmi-ls-manifest.xml`` twice), and fmpy, Ecos and OMSimulator run them.
"""
from __future__ import annotations

import os
import shutil
import stat
import tempfile
import zipfile
import zlib
from pathlib import Path, PurePosixPath

from rotorcosim.components.bounded_read import MAX_ENTRIES, MAX_EXTRACT_BYTES, same_entries


#: caps on what an archive may extract (one place for them: components/bounded_read.py). Our FMUs extract to
#: under 1 MB each (measured: the bearing, damper and toy FMUs of the tests, 24-32 entries, 0.70-0.77 MB, deflate
#: ratio at most 6): the caps leave a wide margin for an SSP of many FMUs and for other tools' FMUs, and stop a
#: bomb long before the disk fills
MAX_TOTAL_BYTES = MAX_EXTRACT_BYTES
#: deflate reaches ~5-10x on code and text, ~1000x on zeros (the bomb's filling)
MAX_RATIO = 200.0
RATIO_FLOOR_BYTES = 1024 ** 2


class ArchiveError(ValueError):
    """The file is not a usable archive (not a zip, unreadable)."""


class UnsafeArchiveError(ArchiveError):
    """An archive entry would be written outside the extraction folder (or is a link)."""


def open_zip(path: str | Path, what: str = "FMU") -> zipfile.ZipFile:
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(f"{what} file {path} is a folder, not an {what} file")
    if not path.is_file():
        raise FileNotFoundError(f"{what} file {path} not found")
    if not zipfile.is_zipfile(path):
        raise ArchiveError(f"{path} is not a zip archive, so not an {what} (an {what} is a zip file)")
    try:
        return zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as exc:
        raise ArchiveError(f"{path}: cannot read the zip archive ({exc})") from None


def check_entries(zf: zipfile.ZipFile, source: str) -> None:
    """Raise :class:`UnsafeArchiveError` for the first entry that could escape an extraction folder, and
    :class:`ArchiveError` for an archive beyond the caps or with clashing names."""
    infos = zf.infolist()
    if len(infos) > MAX_ENTRIES:
        raise ArchiveError(f"{source}: {len(infos)} entries, more than the {MAX_ENTRIES} an archive may hold here "
                           "(the limit of entries)")
    total = 0
    files: dict[str, zipfile.ZipInfo] = {}
    folders: set[str] = set()
    for info in infos:
        name = info.filename.rstrip("/")
        total += info.file_size
        if total > MAX_TOTAL_BYTES:
            raise ArchiveError(f"{source}: would extract more than {MAX_TOTAL_BYTES // 1024 ** 2} MiB "
                               f"(reached at entry {info.filename!r}): refusing it (a zip bomb?)")
        if info.file_size > RATIO_FLOOR_BYTES and info.file_size > MAX_RATIO * max(1, info.compress_size):
            raise ArchiveError(f"{source}: entry {info.filename!r} expands {info.file_size / max(1, info.compress_size):.0f} "
                               f"times ({info.file_size} bytes), more than {MAX_RATIO:g}: refusing it (a zip bomb?)")
        parts = PurePosixPath(name).parts
        if info.is_dir():
            folders.add(name)
        else:
            if name in files:
                _check_duplicate(zf, files[name], info, source)
            else:
                files[name] = info
        folders.update("/".join(parts[:i]) for i in range(1, len(parts)))
    clash = sorted(set(files) & folders)
    if clash:
        raise ArchiveError(f"{source}: {clash[0]!r} is both a file and a folder in the archive")
    for info in infos:
        name = info.filename
        bad = None
        if "\\" in name:
            bad = "contains a backslash"
        elif name.startswith("/") or (len(name) > 1 and name[1] == ":"):
            bad = "is an absolute path"
        elif ".." in PurePosixPath(name).parts:
            bad = "climbs out of the folder with '..'"
        elif info.create_system == 3 and stat.S_ISLNK(info.external_attr >> 16):
            bad = "is a symbolic link"
        if bad:
            raise UnsafeArchiveError(f"{source}: archive entry {name!r} {bad}: refusing to extract it "
                                     "(it could write outside the extraction folder)")


def _check_duplicate(zf: zipfile.ZipFile, first: zipfile.ZipInfo, again: zipfile.ZipInfo, source: str) -> None:
    """A name written twice is one entry when both copies hold the same bytes; otherwise which one is meant is
    unclear (an extractor keeps one, fmpy's reader the other) and the archive is refused."""
    same = first.file_size == again.file_size and first.CRC == again.CRC
    if same:
        try:
            same = same_entries(zf, first, again)   # chunk by chunk: two entries of 512 MiB are not read whole
        except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError) as exc:
            raise ArchiveError(f"{source}: entry {again.filename!r} is damaged ({exc})") from None
    if not same:
        raise ArchiveError(f"{source}: entry {again.filename!r} appears twice with different contents: which one "
                           "is meant is unclear")


def safe_extract(path: str | Path, what: str = "FMU", prefix: str = "rcs_", parent: Path | None = None) -> Path:
    """Extract ``path`` into a fresh temporary folder (returned), in ``parent`` or the system's temporary
    folder; the caller removes it when done."""
    with open_zip(path, what) as zf:
        check_entries(zf, str(path))
        folder = Path(tempfile.mkdtemp(prefix=prefix, dir=parent))
        written = 0
        done: set[str] = set()
        try:
            root = folder.resolve()
            for info in zf.infolist():
                if info.filename in done:   # a duplicate with the same bytes (check_entries): written once
                    continue
                done.add(info.filename)
                target = (root / info.filename).resolve()
                if os.path.commonpath([root, target]) != str(root):
                    raise UnsafeArchiveError(f"{path}: archive entry {info.filename!r} resolves outside the "
                                             "extraction folder: refusing to extract it")
                if info.is_dir():
                    target.mkdir(parents=True, exist_ok=True)
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                written = _copy(zf, info, target, str(path), written)
        except BaseException:
            shutil.rmtree(folder, ignore_errors=True)
            raise
    return folder


def _copy(zf: zipfile.ZipFile, info: zipfile.ZipInfo, target: Path, source: str, written: int) -> int:
    """Extract one entry, counting the bytes against the total cap; malformed data -> ArchiveError."""
    try:
        with zf.open(info) as src, open(target, "wb") as dst:
            while True:
                chunk = src.read(1 << 20)
                if not chunk:
                    break
                written += len(chunk)
                if written > MAX_TOTAL_BYTES:
                    raise ArchiveError(f"{source}: extracting {info.filename!r} went beyond "
                                       f"{MAX_TOTAL_BYTES // 1024 ** 2} MiB: refusing it (a zip bomb?)")
                dst.write(chunk)
    except (zipfile.BadZipFile, zlib.error, EOFError) as exc:
        raise ArchiveError(f"{source}: entry {info.filename!r} is damaged ({exc})") from None
    except NotImplementedError as exc:
        raise ArchiveError(f"{source}: entry {info.filename!r} uses an unsupported compression ({exc})") from None
    except RuntimeError as exc:  # an encrypted entry
        raise ArchiveError(f"{source}: entry {info.filename!r} cannot be read ({exc})") from None
    except (IsADirectoryError, NotADirectoryError, FileExistsError) as exc:
        raise ArchiveError(f"{source}: entry {info.filename!r} clashes with another entry ({exc})") from None
    return written
