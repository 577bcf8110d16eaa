"""A sweep's folder: one sweep at a time (a lock), its previous results (refused, replaced or continued), each
case's folder written whole (write-then-rename) and ``sweep.json`` kept current while the cases run.

* The lock is ``.rotorcosim.lock`` at the top of the folder (lock.py): a second sweep into the folder at once is
  refused naming the first one's process; a sweep that ends (complete, failed or interrupted) removes the file.
* A folder that already holds results is refused, unless ``overwrite`` (which removes a previous sweep's files
  and case folders, and nothing else) or ``resume`` (which keeps the cases its ``sweep.json`` says are complete
  and reruns the others).
* A case's files go into ``.<case>.part`` first, which is then renamed ``<case>``: a case folder is whole or
  absent, whatever stops the sweep.

::

    with SweepFolder(Path("out"), resume=True) as folder:
        done = folder.complete_cases(definitions)   # {name: summary} of the cases kept
        folder.store("F_50", files)
"""
from __future__ import annotations

import errno
import fnmatch
import json
import os
import shutil
from pathlib import Path

from rotorcosim.components.bounded_read import read_json
from rotorcosim.master.run.rundir import LOCK, OutputFolderError, check_folder, ensure_folder, is_run_file
from rotorcosim.master.sweep.lock import FolderLock

#: what a sweep writes at the top of its folder (beside one folder of run files per case, rundir.RUN_FILES, and
#: the files of its case's tables, the case's SWEEP_FILES)
SWEEP_FILES = ("sweep.csv", "sweep.json", "*.part", "*.part.png", ".*.part")
#: the sweep's own record of its cases, rewritten as each case ends
STATE = "sweep.json"
#: a case's state in ``sweep.json``'s ``case_status``: not started yet, sent to a worker, finished with results,
#: finished with an error, stopped by an interrupt (Ctrl-C / SIGTERM) or by the end of the sweep (its scheduler
#: gone, a full disk) before it ended
CASE_STATES = ("pending", "running", "complete", "failed", "interrupted")


class DiskFullError(OSError):
    """The disk holding the sweep's folder is full (the message names the folder)."""


class SweepFolder:
    """``with SweepFolder(out, overwrite=..., resume=..., extra_files=...) as folder:`` holds the sweep's lock
    for the block. ``extra_files``: name patterns of files a case's tables write at the top of the folder (the
    case's ``SWEEP_FILES``), which ``overwrite`` may clear too."""

    def __init__(self, out, overwrite: bool = False, resume: bool = False, extra_files=()):
        if overwrite and resume:
            raise OutputFolderError("--overwrite and --resume exclude each other (one clears the folder, the "
                                    "other continues the sweep in it)")
        self.path = check_folder(out)
        self.overwrite, self.resume = overwrite, resume
        self.extra_files = tuple(extra_files)
        self._lock: FolderLock | None = None
        self._made: list[Path] = []

    # -- the lock ---------------------------------------------------------------------------------------------
    def __enter__(self) -> "SweepFolder":
        p = self.path
        if self.resume and not (p / STATE).is_file():
            raise OutputFolderError(f"--resume: {p} holds no {STATE} (no sweep to continue)")
        missing = p
        while str(missing) not in ("", ".", "/") and not missing.exists():
            self._made.append(missing)
            missing = missing.parent
        ensure_folder(p)
        self._lock = FolderLock(p, "sweep")
        try:
            self._lock.__enter__()
        except BaseException:
            self._lock = None
            self._take_back()
            raise
        try:
            self._previous_results()
        except BaseException:
            self.close(remove_folder=True)
            raise
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self, remove_folder: bool = False) -> None:
        """Release the lock and remove its file (``remove_folder``: and the folders entering made, when they
        are empty: a sweep refused before it starts leaves nothing)."""
        if self._lock is not None:
            self._lock.release()
            self._lock = None
        if remove_folder:
            self._take_back()

    def _take_back(self) -> None:
        for folder in self._made:   # the leaf first; never anything that holds a file
            try:
                folder.rmdir()
            except OSError:
                break

    # -- previous results -------------------------------------------------------------------------------------
    def _ours(self, p: Path) -> bool:
        if p.is_dir() and not p.is_symlink():
            return all(q.is_file() and is_run_file(q.name) for q in p.iterdir())
        return p.is_file() and any(fnmatch.fnmatch(p.name, pat) for pat in (*SWEEP_FILES, *self.extra_files))

    def _previous_results(self) -> None:
        """A sweep's folder holds this sweep's results only: a non-empty one is refused (a second sweep into it
        left the first one's cases beside its own, and a sweep.csv listing only the new ones), with
        ``overwrite`` cleared if it holds nothing but a sweep's files and case folders of run files, with
        ``resume`` kept (:meth:`complete_cases` says which cases)."""
        out = self.path
        old = sorted(p.name for p in out.iterdir() if p.name != LOCK)
        if not old or self.resume:
            return
        if not self.overwrite:
            raise OutputFolderError(f"--out {out} is not empty ({', '.join(old[:4])}{', ...' if len(old) > 4 else ''}"
                                    "): results are never mixed; give --overwrite to replace a previous sweep's "
                                    "results, --resume to continue an interrupted one, or another folder")
        foreign = [n for n in old if not self._ours(out / n)]
        if foreign:
            raise OutputFolderError(f"--overwrite: {out} holds files that are not a sweep's results "
                                    f"({', '.join(foreign[:4])}): not clearing it; choose another folder")
        for n in old:
            p = out / n
            shutil.rmtree(p) if p.is_dir() else p.unlink()

    def complete_cases(self, definitions: dict[str, dict]) -> dict[str, dict]:
        """With ``resume``: ``{case: summary}`` of the cases the previous sweep completed, read from their
        folders; ``definitions`` (``{case: Case.definition()}``) must be the previous sweep's, or the resume is
        refused naming the first difference. Without: ``{}``."""
        if not self.resume:
            return {}
        f = self.path / STATE
        try:
            state = read_json(f, "sweep state")
        except (OSError, ValueError) as exc:
            raise OutputFolderError(f"--resume: {f} is not readable ({exc})") from None
        old = state.get("definitions") if isinstance(state, dict) else None
        if not isinstance(old, dict):
            raise OutputFolderError(f"--resume: {f} does not say what its cases ran (written by an older "
                                    "rotorcosim?): rerun the sweep with --overwrite")
        if list(old) != list(definitions):
            raise OutputFolderError(f"--resume: {self.path} holds a sweep of other cases ({', '.join(list(old)[:4])}"
                                    f"{', ...' if len(old) > 4 else ''}): give the same levels and --set values, "
                                    "or another folder")
        for name, d in definitions.items():
            if json.dumps(old[name], sort_keys=True) != json.dumps(d, sort_keys=True):
                raise OutputFolderError(f"--resume: case {name} of {self.path} ran {old[name]}, not {d}: give the "
                                        "same scenario, duration and schedule, or another folder")
        status = state.get("case_status") or {}
        done = {}
        for name in definitions:
            summary = self.path / name / "summary.json"
            if status.get(name) == "complete" and summary.is_file():
                try:
                    done[name] = read_json(summary, "summary")
                except (OSError, ValueError):
                    continue    # a damaged case is run again
        # the folders an interrupted sweep left half-written (.<case>.part): the cases run again rewrite theirs
        for p in self.path.iterdir():
            if p.is_dir() and p.name.startswith(".") and p.name.endswith(".part"):
                shutil.rmtree(p, ignore_errors=True)
        return done

    # -- writing ----------------------------------------------------------------------------------------------
    def store(self, name: str, files: dict[str, bytes]) -> None:
        """Write a case's files into ``<folder>/<name>`` whole: into a hidden folder first, then renamed. A full
        disk raises :class:`DiskFullError` naming the folder, with nothing of the case left behind."""
        final = self.path / name
        part = self.path / f".{name}.part"
        try:
            shutil.rmtree(part, ignore_errors=True)
            part.mkdir(parents=True)
            for rel, data in files.items():
                target = (part / rel).resolve()
                if part.resolve() not in target.parents:  # a worker is trusted to run cases, not to write anywhere
                    raise ValueError(f"case {name}: a returned file {rel!r} points outside its folder")
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(data)
            if final.exists():
                shutil.rmtree(final)
            os.replace(part, final)
        except OSError as exc:
            shutil.rmtree(part, ignore_errors=True)
            raise named_os_error(exc, self.path, f"storing case {name}") from None

    def write_state(self, state: dict) -> None:
        """``sweep.json`` (written whole: write-then-rename)."""
        from rotorcosim.master.run.outputs import write_json

        try:
            write_json(self.path / STATE, state)
        except OSError as exc:
            raise named_os_error(exc, self.path, f"writing {STATE}") from None


def named_os_error(exc: OSError, folder: Path, doing: str) -> OSError:
    """A full disk as :class:`DiskFullError` naming ``folder`` and what was being done (``doing``, e.g. "writing
    summary.json"), telling to continue with --resume; any other error as an OSError saying ``doing`` too."""
    if exc.errno in (errno.ENOSPC, errno.EDQUOT):
        return DiskFullError(exc.errno, f"the disk holding {folder} is full ({doing}); free space and continue "
                                        "with --resume")
    return OSError(exc.errno, f"{exc.strerror or exc} ({doing})", exc.filename)

