"""The helper process of a fresh machine's first run (master/compiled/ahead.py): it builds what the set-up will need while
this process sets up; this process waits for what the helper has taken and reads it from the cache.

The declared signatures must be those of the real calls, or the helper compiles something nobody loads."""
from __future__ import annotations

import os
import time

import numba
import numpy as np

from rotorcosim.components import cache
from rotorcosim.components.damper import fast, table_cache
from rotorcosim.components.damper.component import FastDamper
from rotorcosim.master.compiled import ahead
from rotorcosim.master.compiled import loop_ops
from rotorcosim.master.cli.run import resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance
from rotorcosim.master.scenario.build import build_simulation
from rotorcosim.master.schedule import Interval, Timeline

# a coarse mesh: its table builds in a fraction of a second
SMALL = (0.08, 0.02, 2e-4, 8, 2)


def test_the_declared_signatures_are_those_of_the_calls():
    d = FastDamper("damper0", {"damper": 0})
    d.setup()
    p, u = d._kernel_p, d.u
    args = (p.NT, p.G, p.TW, p.toff, p.ftab, p.bounds, p.Wc, p.Ws, p.prm, u["X_journal"], u["V_journal"],
            u["X_housing"], u["V_housing"], 1e-3, p.out)
    assert tuple(numba.typeof(a) for a in args) == fast.FAST_STEP_SIG
    sc = resolve("blade_loss")
    apply_unbalance(sc, 2850.0)
    sim = build_simulation(sc, [])
    sim.engine_choice = "compiled"
    h = float(sc.schedule["step"])
    sim.run(Timeline([Interval("TM", 3 * h, h)]))
    assert list(loop_ops.run_chunk.overloads) == [loop_ops.RUN_CHUNK_SIG]
    # the damper names its film kernel and (when the cache lacks it) its table
    jobs = d.prebuild()
    assert (None, fast.fast_step, fast.FAST_STEP_SIG) in jobs


def test_the_helper_builds_a_table_this_process_waits_for_and_reads(tmp_path, monkeypatch):
    monkeypatch.setenv("ROTORCOSIM_CACHE", str(tmp_path / "cache"))
    k = table_cache.key(*SMALL, fast.N_TABLE, fast.EPS_MAX)
    key = f"damper/{k}"
    helper = ahead.Ahead([(key, fast.film_table, SMALL)], folder=str(tmp_path))
    try:
        claim = ahead._file(helper.folder, "claim", key)
        deadline = time.monotonic() + 120
        while not os.path.exists(claim) and time.monotonic() < deadline:  # the helper takes it
            time.sleep(0.01)
        assert not table_cache.exists(k)
        helper.wait(key)  # returns once the helper has built it
        assert table_cache.exists(k)
    finally:
        helper.close()
    assert cache._ahead is None  # the hook is gone with the helper
    t = fast.FilmTable(*SMALL)  # read from the cache
    monkeypatch.setenv("ROTORCOSIM_CACHE", "off")
    fresh = fast.FilmTable(*SMALL)
    assert np.array_equal(t.NT, fresh.NT) and np.array_equal(t.ftab, fresh.ftab) and np.array_equal(t.G, fresh.G)


def test_a_result_this_process_claimed_first_is_left_to_it(tmp_path, monkeypatch):
    monkeypatch.setenv("ROTORCOSIM_CACHE", str(tmp_path / "cache"))
    k = table_cache.key(*SMALL, fast.N_TABLE, fast.EPS_MAX)
    assert ahead._claim(str(tmp_path), f"damper/{k}")  # this process took it before the helper started
    helper = ahead.Ahead([(f"damper/{k}", fast.film_table, SMALL)], folder=str(tmp_path))
    helper.proc.stdin.close()  # no more work (Ahead.share): it ends after its list
    assert helper.proc.wait(timeout=120) == 0  # having skipped the claimed job
    helper.close()
    assert not table_cache.exists(k)


def test_no_helper_when_nothing_is_missing_or_it_is_off(monkeypatch):
    assert ahead.start([], loop=False) is None
    monkeypatch.setenv(ahead.ENV, "0")
    assert ahead.start([FastDamper("d", {"damper": 0})], loop=True) is None


def test_the_helper_ends_with_the_process_that_started_it():
    """A run killed with SIGKILL left its helper building on, orphaned (found: a film table of a huge mesh,
    10.8 GB after 56 minutes); the helper now ends within about a second of its parent, its claims folder
    removed."""
    import subprocess
    import sys
    import textwrap

    script = textwrap.dedent("""
        import os, time
        from rotorcosim.master.compiled import ahead
        h = ahead.Ahead([("table/sleep", time.sleep, (120,))])
        print(h.proc.pid, h.folder, flush=True)
        time.sleep(1)
        os.kill(os.getpid(), 9)
    """)
    res = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    helper, folder = int(res.stdout.split()[0]), res.stdout.split()[1]

    def alive(pid: int) -> bool:  # a zombie (not reaped by whoever inherited it) has ended
        try:
            return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0] != "Z"
        except OSError:
            return False

    deadline = time.monotonic() + 15
    while alive(helper) and time.monotonic() < deadline:
        time.sleep(0.1)
    ended = not alive(helper)
    if not ended:
        os.kill(helper, 9)
    assert ended, "the helper outlived the process that started it"
    # and it took the dead run's claims folder with it (left in the temporary folder for good, before)
    assert not os.path.exists(folder), folder


def test_a_key_this_process_claimed_is_not_waited_for_again(tmp_path):
    """numba compiles a signature again, nested inside another compilation: a second wait on a key this process
    claimed (and builds itself) waited for a "done" only this process would write. Found on a fresh cache with a
    damper swapped for its FMU (tests/fmus/test_swap.py hung); the helper here sleeps, as a busy one would."""
    import time

    h = ahead.Ahead([("table/sleep", time.sleep, (120,)), ("table/mine", time.sleep, (0,))], folder=str(tmp_path))
    try:
        t0 = time.perf_counter()
        deadline = time.perf_counter() + 30
        while not os.path.exists(ahead._file(h.folder, "claim", "table/sleep")) and time.perf_counter() < deadline:
            time.sleep(0.01)   # the helper took its first job and sleeps in it
        h.keys.add("table/own")
        h.wait("table/own")    # claimed here: this process builds it
        h.wait("table/own")    # asked again (nested): returns at once
        assert time.perf_counter() - t0 < 20
    finally:
        h.close()
