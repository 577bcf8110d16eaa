"""One writer at a time in a folder of many runs (a sweep's, a comparison's): ``.rotorcosim.lock`` at its top.

The lock is an advisory ``flock`` on the file, held for the whole block, with the owner's process id in it: a
second holder (another process, or another open of the file in this one) is refused naming that id. The kernel
drops the lock when the process ends however it ends (no stale lock after a SIGKILL); leaving the block removes
the file while it is still held, so a finished sweep leaves no lock file behind.

::

    with FolderLock(Path("out"), "sweep"):
        ...   # another FolderLock on out raises OutputFolderError("... another sweep is writing ...")
"""
from __future__ import annotations

import fcntl
import os
from pathlib import Path

from rotorcosim.master.run.rundir import LOCK, OutputFolderError


class FolderLock:
    """``with FolderLock(folder, what):`` holds the lock of ``folder`` (which must exist) for the block; ``what``
    names the holder in the refusal ("sweep", "comparison")."""

    def __init__(self, folder: Path, what: str):
        self.folder, self.what = Path(folder), what
        self._fd: int | None = None

    def __enter__(self) -> "FolderLock":
        p = self.folder
        try:
            fd = os.open(p / LOCK, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise OutputFolderError(f"--out {p}: cannot create the lock file ({exc.strerror or exc})") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            owner = _read_owner(fd)
            os.close(fd)
            raise OutputFolderError(f"--out {p}: another {self.what} is writing into this folder"
                                    f"{f' (process {owner})' if owner else ''}; wait for it to end or choose "
                                    "another folder") from None
        self._fd = fd
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        return self

    def __exit__(self, *exc) -> None:
        self.release()

    def release(self) -> None:
        """Remove the lock file (while it is held: no one else holds the file removed), then release it."""
        if self._fd is None:
            return
        try:
            (self.folder / LOCK).unlink()
        except OSError:
            pass
        try:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
        finally:
            os.close(self._fd)
            self._fd = None


def _read_owner(fd: int) -> str:
    try:
        return os.pread(fd, 32, 0).decode().strip()
    except OSError:
        return ""
