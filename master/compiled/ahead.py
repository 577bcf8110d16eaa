"""A fresh machine's first run on two cores: a helper process builds, ahead of the set-up, what it and the first
thermo-mechanical interval will need from the on-disk caches (compiled kernels, the damper's film tables).

numba compiles one function at a time in a process, and the film tables' sparse factorisations hold the GIL, so
on a fresh machine the set-up and the first interval build one thing after another on one core.
The components name what their set-up will build from their parameters alone (contract.Component.prebuild: the
damper's film table and film kernel); the master adds the compiled loop (loop_ops.run_chunk, the same types for
every system). Whatever the caches lack, a plain ``python -m`` child builds in that order into the same caches
while this process goes on with its set-up. Each result is built by one process: the one that creates its claim
file first. This process, reaching a result the helper has claimed, waits for it and reads it from the cache
(components/cache.await_ahead, called by the tables' builders and, for the compiled kernels, by
components/numba_internals.compile_for: the explicit compile step of every kernel, trampoline and loop that a
helper may build; only while the helper lives); one the helper has not reached it claims and builds itself. The results are those
of the same code whichever process built it, and the caches keep them bit for bit.

When the caches hold everything (every run after the first) no helper starts; ``ROTORCOSIM_AHEAD=0`` turns it
off, and a helper that fails only leaves this process to build what it had not finished.
"""
from __future__ import annotations

import atexit
import hashlib
import importlib
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
import threading
import time

#: "0" (or off/no/false): no helper process
ENV = "ROTORCOSIM_AHEAD"
#: how often a process waiting for the helper looks for the result (s)
POLL_S = 0.02
#: how often the helper looks whether the process that started it is still there
PARENT_POLL_S = 0.5


def _file(folder: str, kind: str, key: str) -> str:
    return os.path.join(folder, f"{kind}-{hashlib.sha256(key.encode()).hexdigest()[:24]}")


def _claim(folder: str, key: str) -> bool:
    try:
        os.close(os.open(_file(folder, "claim", key), os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        return True
    except FileExistsError:
        return False


class Ahead:
    """The helper process of one set-up, and this process's side of the claims."""

    def __init__(self, jobs, folder: str | None = None):
        from rotorcosim.components import cache

        # the claims' folder (a test may give one holding claims already)
        self.folder = folder or tempfile.mkdtemp(prefix="rotorcosim-ahead-")
        self.keys = {key for key, _, _ in jobs}
        # the keys this process claimed (it builds them itself): a second wait on one of them would wait for a
        # "done" that only this process writes
        self.mine: set[str] = set()
        spec = []
        for key, fn, args in jobs:
            dispatcher = _is_dispatcher(fn)
            f = fn.py_func if dispatcher else fn
            spec.append((key, f.__module__, f.__qualname__, dispatcher, args, None))
        payload = pickle.dumps((self.folder, spec))
        # this process's id on the helper's command line: the helper ends when its parent is no longer this one
        self.proc = subprocess.Popen([sys.executable, "-m", __name__, str(os.getpid())], stdin=subprocess.PIPE,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:  # stdin stays open for share()
            self.proc.stdin.write(payload)
            self.proc.stdin.flush()
        except OSError:  # it died at once: this process builds everything
            pass
        cache.set_ahead(self.wait)
        atexit.register(self.close)

    def share(self, comps_kargs) -> None:
        """More work, known once the first interval's containers are: the kernels of ``comps_kargs``
        [(component, containers)] and their trampolines (master/compiled/kernel_args.py) that the caches
        lack. The helper takes them from the front; this process (compiled.Runner, in reverse order) from the
        back."""
        from numba import types

        from rotorcosim.components import kernels
        from rotorcosim.components.numba_internals import TRAMPOLINE_ARGS, compile_key, in_disk_cache

        from rotorcosim.master.compiled import kernel_args

        if self.proc is None or self.proc.poll() is not None:
            return
        spec = []
        for comp, kargs in comps_kargs:
            ctype = kernel_args.container_type(kargs)
            tramp = kernel_args.functions(ctype)
            fn = type(comp).STEP
            for disp, sig, generated in ((fn, tuple(ctype) + (types.float64, types.float64), None),
                                         (tramp, TRAMPOLINE_ARGS[:4] + (types.TypeRef(ctype),), ctype)):
                key = compile_key(disp, sig)
                if key in self.keys or in_disk_cache(disp, sig):
                    continue
                self.keys.add(key)
                spec.append((key, disp.py_func.__module__, disp.py_func.__qualname__, True, sig, generated))
        if not spec:
            return
        try:  # the port tuples first: the signatures name them (components/kernels.port_tuple)
            self.proc.stdin.write(pickle.dumps(list(kernels.PORT_TUPLES)) + pickle.dumps(spec))
            self.proc.stdin.flush()
        except (OSError, pickle.PicklingError, TypeError, AttributeError):
            pass

    def wait(self, key: str) -> None:
        """Return when this process may build or read ``key`` (components/cache.await_ahead; the compilations'
        keys through components/numba_internals.compile_for)."""
        if key not in self.keys or key in self.mine or self.proc is None:
            return
        if _claim(self.folder, key):
            self.mine.add(key)
            return
        done = _file(self.folder, "done", key)
        while not os.path.exists(done) and self.proc.poll() is None:
            time.sleep(POLL_S)

    def close(self) -> None:
        """Stop the helper (what it builds now is no longer this run's) and undo the hooks."""
        if self.proc is None:
            return
        from rotorcosim.components import cache

        cache.set_ahead(None)
        try:
            self.proc.stdin.close()
        except OSError:
            pass
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self.proc = None
        shutil.rmtree(self.folder, ignore_errors=True)
        atexit.unregister(self.close)


def start(components, loop: bool) -> Ahead | None:
    """A helper building what the set-up of ``components`` (and, with ``loop``, the compiled loop) will need and
    the caches lack; None when nothing is missing, the helper is off or the machine has one core."""
    if os.environ.get(ENV, "1").lower() in ("0", "off", "no", "false") or (os.cpu_count() or 1) < 2:
        return None
    jobs, seen = [], set()

    def add(key, fn, args):
        if key is None:  # a compilation: numba is in use already (the component's own kernels import it)
            from rotorcosim.components.numba_internals import compile_key, in_disk_cache

            if in_disk_cache(fn, args):
                return
            key = compile_key(fn, args)
        if key not in seen:
            seen.add(key)
            jobs.append((key, fn, args))

    for c in components:
        for job in c.prebuild():
            add(*job)
    if loop and any(getattr(type(c), "STEP", None) is not None for c in components):
        # the compiled loop runs only components with kernels (numba is then in use; an FMU-only system never
        # imports it)
        from rotorcosim.master.compiled import loop_ops

        add(None, loop_ops.run_chunk, loop_ops.RUN_CHUNK_SIG)
    if not jobs:
        return None
    # the compilations first, the tables (and other builds) last: this process builds a table itself when it gets
    # there first, while a kernel it needs soon after (the damper's, right after its table) takes longest
    jobs.sort(key=lambda job: not isinstance(job[0], str) or not job[0].startswith("numba/"))
    try:
        return Ahead(jobs)
    except (OSError, pickle.PicklingError, TypeError, AttributeError):
        return None


def _is_dispatcher(fn) -> bool:
    """A numba dispatcher (compiled for a signature), not a plain function (called)? Without importing numba."""
    return hasattr(fn, "py_func") and hasattr(fn, "overloads")


def _end_with_parent(parent: int, folders: list[str]) -> None:
    """End this helper when the process that started it is gone: a run killed with SIGKILL (or a sweep's worker)
    left it building on, orphaned (a film table of a huge mesh: 10.8 GB after 56 minutes). A thread polls the
    parent's id (not PR_SET_PDEATHSIG: it fires when the starting *thread* ends, and a sweep case starts the
    helper from a worker thread). ``parent``: the starter's id, given on the command line: read here with
    getppid() it was already the orphan's new parent when the starter died while this helper was still importing
    (under load, over a second: the helper then built on). ``folders``: the claims' folder once the helper has
    read it, removed on the way out (a killed run never closes its side)."""

    def watch() -> None:
        while True:
            time.sleep(PARENT_POLL_S)
            if os.getppid() != parent:
                # the claims were the dead run's alone: its close() never came to remove them
                for folder in folders:
                    shutil.rmtree(folder, ignore_errors=True)
                os._exit(0)

    threading.Thread(target=watch, name="rotorcosim-ahead-parent", daemon=True).start()


def _helper() -> None:
    from rotorcosim.components import kernels

    from rotorcosim.master.compiled import kernel_args
    from rotorcosim.master.core import threads

    folders: list[str] = []   # the claims' folder, once read: removed if the parent dies first
    _end_with_parent(int(sys.argv[1]) if len(sys.argv) > 1 else os.getppid(), folders)
    stream = sys.stdin.buffer
    folder, jobs = pickle.load(stream)
    folders.append(folder)
    with threads.one_thread():
        while True:
            for key, module, qualname, dispatcher, args, generated in jobs:
                if not _claim(folder, key):
                    continue
                try:
                    if generated is not None:  # the trampoline of these containers (kernel_args)
                        obj = kernel_args.functions(generated)
                    else:
                        obj = importlib.import_module(module)
                        for part in qualname.split("."):
                            obj = getattr(obj, part)
                    if dispatcher:
                        obj.compile(args)
                    else:
                        obj(*args)
                except Exception:  # the waiting process finds no result and builds it itself
                    pass
                finally:
                    open(_file(folder, "done", key), "w").close()
            try:  # more work (Ahead.share): the port tuples its types name, then the jobs
                for key in pickle.load(stream):
                    kernels.port_tuple(*key)
                jobs = pickle.load(stream)
            except (EOFError, OSError, pickle.UnpicklingError):
                return


if __name__ == "__main__":
    _helper()
