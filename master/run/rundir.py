"""The output folder of a run: never mixed with another run's results, never written by two runs at once.

* ``--out`` must name a folder (not an empty string, not a file) we can write into;
* a folder that already holds results is refused unless ``overwrite`` (which first removes the old results:
  only files a run writes, so a folder with anything else in it is never emptied) or ``resume`` (which
  continues the run whose checkpoint is there);
* a lock file (``.rotorcosim.lock``, an advisory ``flock`` held for the whole run, with the owner's process id
  in it) stops a second run on the same folder while the first is alive; the kernel releases it when the
  process ends however it ends, so a killed run never leaves a stale lock, and a run that ends removes the file
  (a finished run's folder holds its results only);
* ``summary.json`` is written with ``status = "running"`` when the run starts, and with its final status
  (``complete``, ``interrupted``, ``failed``) when it ends: after a SIGKILL the folder says "running" with a
  process id that is gone, never an older run's results as if current;
* a run refused at set-up (a bad parameter found when the components are set up) leaves the folder as it found
  it (the run's session removes its summary, this takes back the lock and the folders it made); a folder holding only
  the failed summary of such a run (as earlier versions left it) is taken by the next run without --overwrite.
"""
from __future__ import annotations

import fcntl
import fnmatch
import os
import sys
from pathlib import Path

from rotorcosim.components.bounded_read import read_json

LOCK = ".rotorcosim.lock"
#: what a run writes into its folder (a folder holding only these may be cleared by --overwrite)
RUN_FILES = ("summary.json", "timeseries.h5", "timeseries.csv", "checkpoint.pkl", "*.png", "*.part", LOCK)
STATUSES = ("running", "complete", "interrupted", "failed")


class OutputFolderError(ValueError):
    """An output folder that cannot be used (the message says which and why)."""


def is_run_file(name: str) -> bool:
    """True for a file name a run writes into its folder (:data:`RUN_FILES`): one ``--overwrite`` may clear."""
    return any(fnmatch.fnmatch(name, pat) for pat in RUN_FILES)


def check_folder(path, what: str = "--out") -> Path:
    """``path`` as a Path if it can name a folder of results (not empty, not a file), without creating anything:
    for a command that checks the rest of its input before it makes the folder (ensure_folder)."""
    p = Path(path)
    if str(path).strip() == "":
        raise OutputFolderError(f"{what} is empty: give the folder the results go to")
    if p.exists() and not p.is_dir():
        raise OutputFolderError(f"{what} {p} is a file, not a folder")
    return p


def ensure_folder(path, what: str = "--out") -> Path:
    """``path`` as a folder we can write into, created if missing; else an OutputFolderError naming ``what``
    (the option or argument that gave it) and why. Every command that writes a folder of results uses it."""
    p = check_folder(path, what)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise OutputFolderError(f"{what} {p}: a part of the path is a file, not a folder") from None
    except PermissionError:
        raise OutputFolderError(f"{what} {p}: no permission to create the folder") from None
    except OSError as exc:
        raise OutputFolderError(f"{what} {p}: cannot create the folder ({exc.strerror or exc})") from None
    if not os.access(p, os.W_OK | os.X_OK):
        raise OutputFolderError(f"{what} {p}: the folder is not writable")
    return p


class RunFolder:
    """``with RunFolder(out, overwrite=..., resume=...) as folder:`` holds the lock for the block."""

    def __init__(self, out, overwrite: bool = False, resume: bool = False):
        if out is None or str(out).strip() == "":
            raise OutputFolderError("--out is empty: give the folder the results go to")
        if overwrite and resume:
            raise OutputFolderError("--overwrite and --resume exclude each other (one clears the folder, the "
                                    "other continues the run in it)")
        self.path = Path(out)
        self.overwrite = overwrite
        self.resume = resume
        self._fd = None
        #: set by the run once it has written its first summary.json (session.py): until then an error takes
        #: back what entering made (the folders, the lock file), so that a run refused at set-up leaves nothing
        self.started = False
        self._made: list[Path] = []
        self._lock_made = False

    def __enter__(self) -> "RunFolder":
        if self.resume and not self.path.exists():  # nothing to continue: create nothing
            raise OutputFolderError(f"--resume: {self.path} does not exist, so no checkpoint.pkl (no interrupted run to continue)")
        missing = self.path
        while str(missing) not in ("", ".", "/") and not missing.exists():
            self._made.append(missing)
            missing = missing.parent
        p = ensure_folder(self.path)
        self._lock_made = not (p / LOCK).exists()
        self._lock(p)
        try:
            self._claim()
        except BaseException:
            self.__exit__(*sys.exc_info())
            raise
        return self

    def _lock(self, p: Path) -> None:
        """Hold the folder's lock file, or raise naming the run that holds it."""
        while True:
            try:
                self._fd = os.open(p / LOCK, os.O_RDWR | os.O_CREAT, 0o644)
            except OSError as exc:
                raise OutputFolderError(f"--out {p}: cannot create the lock file ({exc.strerror or exc})") from None
            try:
                fcntl.flock(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                owner = _read_owner(self._fd)
                os.close(self._fd)
                self._fd = None
                raise OutputFolderError(f"--out {p}: another run is writing into this folder"
                                        f"{f' (process {owner})' if owner else ''}; wait for it or choose another "
                                        "folder") from None
            # a run that ended between our open and our flock removed the file we hold: a lock on it would
            # exclude no one (the next run creates a new file); take the one the folder has now
            try:
                if os.stat(p / LOCK).st_ino == os.fstat(self._fd).st_ino:
                    return
            except FileNotFoundError:
                pass
            os.close(self._fd)
            self._fd = None

    def _claim(self) -> None:
        p = self.path
        os.ftruncate(self._fd, 0)
        os.pwrite(self._fd, f"{os.getpid()}\n".encode(), 0)
        present = sorted(x.name for x in p.iterdir() if x.name != LOCK)
        if self.resume:
            if "checkpoint.pkl" not in present:
                raise OutputFolderError(f"--resume: {p} has no checkpoint.pkl (no interrupted run to continue)")
            return
        if not present or (not self.overwrite and self._failed_before_start(present)):
            for name in present:
                (p / name).unlink()
            return
        foreign = [n for n in present if not is_run_file(n) or (p / n).is_dir()]
        if not self.overwrite:
            raise OutputFolderError(f"--out {p} is not empty ({', '.join(present[:5])}"
                                    f"{', ...' if len(present) > 5 else ''}): results are never mixed; give "
                                    "--overwrite to replace a previous run's results, --resume to continue an "
                                    "interrupted run, or another folder")
        if foreign:
            raise OutputFolderError(f"--overwrite: {p} holds files that are not a run's results "
                                    f"({', '.join(foreign[:5])}): not clearing it; choose another folder")
        for name in present:
            (p / name).unlink()

    def _failed_before_start(self, present: list[str]) -> bool:
        """Only the summary of a run that failed before its first step (a bad parameter, an unknown signal):
        it holds no results, so the corrected run may take the folder without --overwrite."""
        if present != ["summary.json"]:
            return False
        try:
            s = read_json(self.path / "summary.json", "summary")
        except (OSError, ValueError):
            return False
        return (isinstance(s, dict) and s.get("status") == "failed" and not s.get("timeline")
                and s.get("t_end_s") in (0, 0.0, None) and not s.get("checkpoint"))

    def release(self) -> None:
        """Release the folder's lock (another run may then use the folder) and remove its file: removed while
        still held, so that no run can hold a lock on a file that is gone (``_lock`` checks it holds the file
        the folder has)."""
        if self._fd is not None:
            try:
                try:
                    os.unlink(self.path / LOCK)
                except OSError:  # already gone, or a read-only folder now: the lock is released all the same
                    pass
                fcntl.flock(self._fd, fcntl.LOCK_UN)
            finally:
                os.close(self._fd)
                self._fd = None

    def __exit__(self, exc_type=None, *exc) -> None:
        self.release()
        if exc_type is not None and not self.started:
            self._take_back()

    def _take_back(self) -> None:
        """Remove the lock file and the folders entering made (only what is empty: never anything else)."""
        if self._lock_made:
            try:
                (self.path / LOCK).unlink()
            except OSError:
                pass
        for folder in self._made:   # the leaf first
            try:
                folder.rmdir()
            except OSError:
                break


def _read_owner(fd: int) -> str:
    try:
        return os.pread(fd, 32, 0).decode().strip()
    except OSError:
        return ""

