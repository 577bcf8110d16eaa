"""Extract an FMU or SSP archive without letting any entry write outside a fresh temporary folder.

Every entry is checked *before* anything is written: absolute paths (``/x``, ``C:x``, ``\\\\server``), ``..``
components (zip-slip), backslashes (not portable; can hide ``..\\``), symbolic links (a link inside the folder can
point anywhere, and a later entry written "through" it escapes), and, after normalisation, the final path must
still lie inside the folder. A bad archive raises :class:`UnsafeArchiveError` naming the entry, and the folder
is removed.
"""
from __future__ import annotations

import os
import shutil
import stat
import tempfile
import zipfile
from pathlib import Path, PurePosixPath


class ArchiveError(ValueError):
    """The file is not a usable archive (not a zip, unreadable)."""


class UnsafeArchiveError(ArchiveError):
    """An archive entry would be written outside the extraction folder (or is a link)."""


def open_zip(path: str | Path, what: str = "FMU") -> zipfile.ZipFile:
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{what} file {path} not found")
    if not zipfile.is_zipfile(path):
        raise ArchiveError(f"{path} is not a zip archive, so not an {what} (an {what} is a zip file)")
    try:
        return zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as exc:
        raise ArchiveError(f"{path}: cannot read the zip archive ({exc})") from None


def check_entries(zf: zipfile.ZipFile, source: str) -> None:
    """Raise :class:`UnsafeArchiveError` for the first entry that could escape an extraction folder."""
    for info in zf.infolist():
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


def safe_extract(path: str | Path, what: str = "FMU", prefix: str = "rcs_", parent: Path | None = None) -> Path:
    """Extract ``path`` into a fresh temporary folder (returned), in ``parent`` or the system's temporary
    folder; the caller removes it when done."""
    with open_zip(path, what) as zf:
        check_entries(zf, str(path))
        folder = Path(tempfile.mkdtemp(prefix=prefix, dir=parent))
        try:
            root = folder.resolve()
            for info in zf.infolist():
                target = (root / info.filename).resolve()
                if os.path.commonpath([root, target]) != str(root):
                    raise UnsafeArchiveError(f"{path}: archive entry {info.filename!r} resolves outside the "
                                             "extraction folder: refusing to extract it")
                if info.is_dir():
                    target.mkdir(parents=True, exist_ok=True)
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                with zf.open(info) as src, open(target, "wb") as dst:
                    shutil.copyfileobj(src, dst)
        except BaseException:
            shutil.rmtree(folder, ignore_errors=True)
            raise
    return folder
