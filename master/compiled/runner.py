"""The compiled path of a thermo-mechanical interval (two execution paths, one semantics: docs/explanation/compiled-path.md).

When every component stepped in an interval offers a compiled kernel (components/kernels.py), the interval's
base steps run in one numba loop instead of the generic Python loop (algorithm.Engine.base_step), with the
same semantics, operation for operation:

* the Gauss-Seidel order and the multi-rate firing (component c fires at base step k when (k + 1) % n_c == 0,
  over [t_end - n_c h, t_end], t_end = t0 + (k + 1) h);
* each consumer's inputs gathered just before it fires, and each link's bookkeeping after its producer fired
  (averages, extrapolation history, the thermal-only hold's windows and restart offsets; a window counted in
  turns of the cycle's angle reads that angle from the port array), by the very functions of master/core/links.py
  and master/core/window.py the generic loop calls, on the same state layout (each link's state and its hand-off
  window's record are copied into the loop's tables and back around each chunk);
* after each firing, as algorithm.Engine._fire: the step count, the finiteness of the outputs other components
  read;
* every ``check_every`` base steps the finiteness of all outputs;
* the same kernel functions as the components' generic do_step.

The loop is one fixed compiled function for every system (loop_ops.run_chunk), compiled once per package version
(numba's disk cache): all components' ports are views of one flat array, the links are rows of index tables
processed by fixed compiled functions (loop_ops), and each kernel is called through a trampoline on the
component's containers packed into one memory block (kernel_args), all given by address, so the loop's arguments
are named records of plain arrays and numbers whatever the system. It runs in chunks: the signals the observers read are written
into a buffer, one row per base step, which the observers then consume (Observer.step_block); between chunks the
components' state and outputs are their own arrays (the kernels work on them in place; the port arrays are the
flat array's views), so checkpoints and observers see what the generic path would show them. A kernel that needs
Python for a step (a quasi-static re-seating after a thermal-only interval, for example) or fails returns its
status; the step is finished or the error raised in Python, as the generic path would, and the loop resumes after
that component.

Not compiled (the generic loop runs, and the reason is reported): a component without a kernel (FMUs, Python
plug-ins), Jacobi or iterative coupling, converted or non-Real links, inputs from components not stepped in the
interval, an observer without step_block (the cycle's RevolutionCounter reads the angle's column, so an angle
whose component does not step in the interval would be one; the hold refuses that run), a steadiness test that
samples an output not stepped in the interval.
"""
from __future__ import annotations

import weakref

import numba
import numpy as np

from rotorcosim.components.contract import ContractError
from rotorcosim.components.kernels import EVENT, PYTHON
from rotorcosim.components.numba_internals import TypingError, compile_for, native_address

from rotorcosim.master.compiled import kernel_args
from rotorcosim.master.compiled import loop_ops as op
from rotorcosim.master.core import links, window
from rotorcosim.master.core.algorithm import ComponentFailed, SimulationDiverged, SimulationFailed, step_failure

#: base steps per compiled chunk (rows of the observers' buffer): ~1 ms of wall time between observer calls
CHUNK = 2048


# -- kernels ---------------------------------------------------------------------------------------------------
def kernel_address(fn, args) -> int:
    """The address of kernel ``fn`` compiled for the types of ``args`` + (t, h) (compiled here, or loaded from its
    disk cache, if not yet), for numba_internals.call_kernel, which needs an int64 status."""
    sig = tuple(numba.typeof(a) for a in args) + (numba.types.float64, numba.types.float64)
    return native_address(fn, sig, returns=numba.types.int64)


# -- the plan of an interval ----------------------------------------------------------------------------------
class Plan:
    """What the loop needs: components in order, their rates, the links into them, the watched and observed
    outputs, the layout of all ports in one flat array and the tables over it (loop_ops)."""

    def __init__(self, sim, active, mult):
        eng = sim.engine
        comps = sim.system.components
        self.names = list(eng.active)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.mult = {n: int(mult.get(n, 1)) for n in self.names}
        self.comps = [comps[n] for n in self.names]
        self.kernels = [type(c).STEP for c in self.comps]
        self.links = []
        self.size = []
        lid = {}

        def link_id(link):
            if id(link) not in lid:
                lid[id(link)] = len(self.links)
                self.links.append(link)
                self.size.append(comps[link.con.src_component].variable(link.sport).size)
            return lid[id(link)]

        self.inputs = [[(link_id(l), l) for l in eng.inputs_of(n)] for n in self.names]
        self.outgoing = [[(link_id(l), l) for l in eng.outgoing_of(n)] for n in self.names]
        # the thermal-only hold's hand-backs (a restart offset after a thermal-only interval): known from the
        # system, so that every thermo-mechanical interval of a run has the same tables
        self.handbacks = {lid[id(l)] for l in sim.hold.handbacks if id(l) in lid}
        self.watch = [list(eng.watched_of(n)) for n in self.names]
        self.outputs = [[v.name for v in c.variables if v.causality == "output" and v.carried and v.type == "Real"]
                        for c in self.comps]
        # the flat array X of all ports: every Real output first, in the observers' buffer order (the buffer's
        # row is then X[:width]), the components' other outputs, then their inputs
        self.ports = []      # (component index, "u" or "y", port, offset, size)
        self.offset = {}     # (component index, "u" or "y", port) -> offset
        off = 0

        def place(i, kind, port):
            nonlocal off
            size = self.comps[i].variable(port).size
            self.offset[(i, kind, port)] = off
            self.ports.append((i, kind, port, off, size))
            off += size

        self.observed = {}
        for i, n in enumerate(self.names):
            for port in self.outputs[i]:
                place(i, "y", port)
                self.observed[f"{n}.{port}"] = (i, port, self.offset[(i, "y", port)], self.comps[i].variable(port).size)
        self.width = max(1, off)
        for i, c in enumerate(self.comps):
            _, _, ins, outs = c.kernel_ports()
            for port in outs:
                if (i, "y", port) not in self.offset:
                    place(i, "y", port)
            for port in ins:
                place(i, "u", port)
        self.nx = max(1, off)
        self._tables()

    def _tables(self):
        nl, nc = len(self.links), len(self.names)
        LI = np.zeros((max(1, nl), op.NL), dtype=np.int64)
        idx = []
        vo = 0
        for j, link in enumerate(self.links):
            i_src = self.index[link.con.src_component]
            i_dst = self.index[link.con.dst_component]
            n = self.size[j]
            row = LI[j]
            row[op.L_SRC] = self.offset[(i_src, "y", link.sport)]
            row[op.L_DST] = self.offset[(i_dst, "u", link.dport)]
            row[op.L_N] = n
            row[op.L_TAKE], row[op.L_PROD] = link.take_kind, link.produce_kind
            row[op.L_HB] = j in self.handbacks
            row[op.L_VOFF] = vo
            vo += links.NV * n
            row[op.L_ANG] = -1
            if link.window is not None:
                row[op.L_WIN] = 1
                if link.window.turns is not None:   # its cycles end at the turns of the cycle's angle
                    comp, _, port = link.window.turns[0].ref.partition(".")
                    key = (self.index.get(comp, -1), "y", port)
                    if key not in self.offset:
                        raise ContractError(f"{link.con.src}: its hand-off window counts the turns of "
                                            f"{comp}.{port}, not an output stepped in this interval")
                    row[op.L_ANG] = self.offset[key]
                row[op.L_WP0] = len(idx)
                for p in link.window.ports:
                    idx += [self.offset[(i_src, "u", p)], self.comps[i_src].variable(p).size]
                row[op.L_WP1] = len(idx)
                row[op.L_CW] = 1 + sum(self.comps[i_src].variable(p).size for p in link.window.ports)
        self.nv = max(1, vo)
        CT = np.zeros((max(1, nc), op.NC), dtype=np.int64)
        for i in range(nc):
            CT[i, op.C_IN0] = len(idx)
            idx += [j for j, _ in self.inputs[i]]
            CT[i, op.C_IN1] = len(idx)
            CT[i, op.C_OUT0] = len(idx)
            idx += [j for j, _ in self.outgoing[i]]
            CT[i, op.C_OUT1] = len(idx)
            CT[i, op.C_W0] = len(idx)
            for port in self.watch[i]:
                idx += [self.offset[(i, "y", port)], self.comps[i].variable(port).size]
            CT[i, op.C_W1] = len(idx)
        self.LI, self.CT = LI, CT
        self.IDX = np.array(idx or [0], dtype=np.int64)
        self.mult_arr = np.array([self.mult[n] for n in self.names], dtype=np.int64)


def _link_state(link, m, v, w):
    """A link's state (links.py's layout) into its row m of the loop's rows and its slice v of the vectors, with a
    hand-back's restart offset (links.R0, RLEN, V_DELTA) from the hold's Restart; its hand-off window's record
    (window.py) into the record w."""
    m[:] = link.state
    v[:] = link.vectors
    if link.window is not None:
        link.window.w.to_record(w)
        w["nout"] = 0
    n = link.n
    ramp = link.ramp
    if ramp is not None:
        m[links.R0], m[links.RLEN] = ramp.t0, ramp.length
        v[links.V_DELTA * n:(links.V_DELTA + 1) * n] = ramp.delta
    else:
        m[links.R0] = m[links.RLEN] = 0.0


def _link_back(link, m, v, w, cycles):
    """The loop's state back into the link's own arrays (the generic loop, the hold and checkpoints read them),
    its window's record into the hold's Window and the rotor cycles the loop completed into its hand-off window."""
    link.state[:] = m.tolist()
    link.vectors[:] = v.tolist()
    ho = link.window
    if ho is not None:
        for r in range(int(w["nout"])):
            ho.cycles.append((cycles[r, 1:].copy(), float(cycles[r, 0])))
        w["nout"] = 0
        ho.w.from_record(w)


class Runner:
    """Runs base steps k..nsteps of one interval through the compiled loop."""

    def __init__(self, sim, plan: Plan, step: float):
        # a weak reference: the module's cache of runners (_RUNNERS) is keyed weakly by the simulation
        self._sim = weakref.ref(sim)
        self.plan = plan
        self.h = step
        self.packed = [kernel_args.Packed() for _ in plan.comps]
        # the observers' buffer and the refs each observer reads
        self.buf = np.zeros((CHUNK, plan.width))
        self.status = np.zeros(3, dtype=np.int64)
        self.X = np.zeros(plan.nx)
        self._views = {}
        #: the plan's components that declare event indicators
        self.watched = [c for c in plan.comps if c.event_indicators]
        #: the base step the generic loop is to take next (an event in it, or a component's Python step while an
        #: indicator is live), or None
        self.pending = None

    @property
    def sim(self):
        """The simulation this runner serves (held weakly: a runner kept in the cache does not keep it alive)."""
        return self._sim()

    def _columns(self, rows):
        b = self.buf[:rows]
        return {ref: b[:, off:off + size] for ref, (_, _, off, size) in self.plan.observed.items()}

    def _adopt(self):
        """Every component's ports as views of X (the kernels' containers are built from them), taking the
        values of any port array that is not the view (a port set or replaced in Python since)."""
        X, views = self.X, self._views
        for i, kind, port, off, size in self.plan.ports:
            d = (self.plan.comps[i].u if kind == "u" else self.plan.comps[i].y)
            a = d[port]
            view = views.get((i, kind, port))
            if a is view and view is not None:
                continue
            a = np.asarray(a, dtype=float).reshape(-1)
            if a.shape[0] != size:
                raise ContractError(f"{self.plan.names[i]}.{port}: {a.shape[0]} values, its variable has {size}")
            X[off:off + size] = a
            view = X[off:off + size]
            views[(i, kind, port)] = view
            d[port] = view

    def _windows(self, G, goff):
        """The hand-off windows' rings as views of G (the loop records into them in place)."""
        for j, link in enumerate(self.plan.links):
            ho = link.window
            if ho is None:
                continue
            go, nr, n = goff[j]
            ring = ho.ring
            view = self._views.get(("ring", j))
            if ring is view and view is not None:
                continue
            if ring.shape != (nr, n):
                raise RuntimeError(f"{link.con.src}: the hand-off ring changed shape during the interval")
            G[go:go + nr * n] = ring.reshape(-1)
            view = G[go:go + nr * n].reshape(nr, n)
            self._views[("ring", j)] = view
            ho.ring = view

    def run(self, k: int, nsteps: int, t_start: float, stop=None, period: int = 0) -> int:
        """Base steps k .. nsteps - 1; returns the steps completed (nsteps, or fewer where ``stop`` ended the
        interval: its reason in ``self.why``; or where base step ``self.pending`` is the generic loop's, below).
        ``self.k`` holds the steps completed when it raises.

        Events (master/core/events.py): while a component's event indicator is live, the loop's state is saved
        before each chunk (the components' snapshots and the link tables). A kernel that returns EVENT at base step
        kk (an indicator changed sign over it) stops the chunk; the chunk is rolled back to its saved state and run
        again to the start of kk, and the run returns with ``pending = kk``: the caller takes that step in the
        generic loop, where the event locator finds the event, and comes back. A component's Python step (status
        PYTHON) while an indicator is live goes the same way, so that the generic step starts on a base step. With
        no live indicator nothing is saved, and a chunk runs as it would without events.
        ``stop`` (the automatic schedule's test, master/schedule/auto.py) is fed each chunk's rows of the signals it samples
        (``sample_block``) and checked where the generic loop checks it, after every ``period``-th base step: the
        chunks end there."""
        sim, plan, h = self.sim, self.plan, self.h
        self.k = k
        self.why = ""
        self.pending = None
        limit = nsteps    # the step the rolled back chunk runs to (an event's)
        saved = None
        for key in [key for key in self._views if key[0] == "ring"]:  # the last interval's rings, in its own G
            del self._views[key]
        eng = sim.engine
        comps = plan.comps
        for c, n in zip(comps, plan.names):
            c.kernel_prepare(plan.mult[n] * h)
        # the links' bookkeeping, rings and cycle means as tables (loop_ops)
        nl = len(plan.links)
        LI = plan.LI.copy()
        M = np.zeros((max(1, nl), links.NM))
        W = np.zeros(max(1, nl), window.DTYPE)
        V = np.zeros(plan.nv)
        goff, go, co = {}, 0, 0
        for j, link in enumerate(plan.links):
            n = plan.size[j]
            vo = int(LI[j, op.L_VOFF])
            _link_state(link, M[j], V[vo:vo + links.NV * n], W[j])
            if link.window is not None:
                nr = link.window.ring.shape[0]
                goff[j] = (go, nr, n)
                LI[j, op.L_GOFF], LI[j, op.L_GNR] = go, nr
                go += nr * n
                LI[j, op.L_COFF] = co
                # at most one cycle a sample when counted in turns (window.record)
                per = link.window.w.n_cycle if link.window.turns is None else 1
                co += (CHUNK // per + 2) * int(LI[j, op.L_CW])
        G = np.zeros(max(1, go))
        C = np.zeros(max(1, co))
        count = np.zeros(len(comps), dtype=np.int64)
        check = int(eng.settings.check_every)
        r0 = -1
        addrs = None
        # the loop compiled (or loaded from its disk cache) as an explicit step: a helper process of a fresh machine
        # may be building it (ahead.py)
        compile_for(op.run_chunk, op.RUN_CHUNK_SIG)
        tab = op.Tables(LI, plan.CT, plan.IDX, plan.mult_arr)
        state = op.LinkState(M, V, W, G, C)
        res = op.Results(count, self.buf, self.status)
        # containers packed in an earlier interval of the run (a reused runner) and unchanged keep their block
        PA = np.array([pk.address if pk.kargs is not None else 0 for pk in self.packed], dtype=np.int64)
        while k < limit:
            k1 = min(limit, k + CHUNK)
            if period:
                k1 = min(k1, (k // period + 1) * period)
            # an indicator live: the state the chunk can be rolled back to (base step k, r0 = -1 then)
            saved = (k, self._save(M, V, W, G)) if r0 < 0 and any(len(c.indicators()) for c in self.watched) else None
            self._adopt()
            self._windows(G, goff)
            kargs = [c.kernel_args() for c in comps]
            if addrs is None:  # typing the containers costs ~0.5 ms per chunk: again only after a Python step (below)
                helper = sim.ahead
                if helper is not None:  # a fresh machine: the helper compiles from the front (ahead.py) ...
                    helper.share(list(zip(comps, kargs)))
                # ... and this process from the back
                addrs = [self._address(c, ka) for c, ka in zip(comps[::-1], kargs[::-1])][::-1]
                TA = np.array([a[0] for a in addrs], dtype=np.int64)
                KA = np.array([a[1] for a in addrs], dtype=np.int64)
            for i in reversed(range(len(comps))):
                if self.packed[i].update(kargs[i], addrs[i][2]):
                    PA[i] = self.packed[i].address
            chunk = op.Chunk(int(k), int(k1), int(r0), float(t_start), float(h), check, int(plan.width))
            op.run_chunk(chunk, self.X, tab, state, op.Kernels(TA, PA, KA), res)
            if not sim.first_compiled.is_set():  # the loop and the interval's kernels are loaded: the helper is done
                sim.compiled_done()
            code, kk, i = (int(x) for x in self.status)
            if saved is not None and (code == EVENT or code == PYTHON):
                # base step kk is the generic loop's: the chunk again to its start, from the saved state
                k, limit = saved[0], kk
                self._restore(saved[1], M, V, W, G, count)
                addrs = None
                continue
            if code == EVENT:
                raise ContractError(f"{plan.names[i]}: its kernel reported an event at t = {t_start + (kk + 1) * h:.9g} "
                                    "s with no live event indicator")
            done = kk  # base steps completed
            self._back(LI, M, V, W, C, count)
            self.k = done
            self._observe(k, done, t_start)
            if stop is not None and done > k:
                stop.sample_block(self._columns(done - k))
            k = done
            r0 = -1
            if code == 0:
                if period and k % period == 0:
                    self.why = stop.check(sim, sim.t) or ""
                    if self.why:
                        return k
                continue
            addrs = None  # a component steps in Python below: its containers may come back with other types
            # base step kk stopped at component i
            name = plan.names[i] if i >= 0 else None
            t_end = t_start + (kk + 1) * h
            sim.t = t_start + kk * h
            if code == -2:
                eng.check_finite(t_end)
                raise SimulationDiverged(f"non-finite output at t = {t_end:.9g} s")
            hc = plan.mult[name] * h
            t = t_end - hc
            if code == -1:
                eng.diverged(name, t, t + hc)
            comp = comps[i]
            try:
                comp.kernel_status(code, t, hc)
            except SimulationFailed:
                raise
            except Exception as exc:
                raise step_failure(name, t, exc) from exc
            if code != PYTHON:
                raise ComponentFailed(f"{name} failed in do_step at t = {t:.9g} s (kernel status {code})")
            comp.time = t + hc
            r0 = i  # resume after the component's step: its bookkeeping, then the next components
        sim.t = t_start + k * h
        if limit < nsteps:
            self.pending = limit
        return k

    def _save(self, M, V, W, G):
        """What a chunk changes: the components' snapshots and the link tables (rows, vectors, window records and
        rings; the counts are zero at a chunk's start)."""
        return [c.get_state() for c in self.plan.comps], M.copy(), V.copy(), W.copy(), G.copy()

    def _restore(self, saved, M, V, W, G, count):
        """Back to :meth:`_save`'s state: the components' ports come back as arrays of their own, which the next
        chunk adopts into the port array, their state as other containers, which it packs."""
        states, m, v, w, g = saved
        for c, st in zip(self.plan.comps, states):
            c.set_state(st)
        M[:] = m
        V[:] = v
        W[:] = w
        G[:] = g
        count[:] = 0

    _ADDR: dict = {}

    @classmethod
    def _address(cls, comp, kargs):
        """(trampoline address, kernel address, numba type of the containers) for these containers' types (one
        look-up per type and process)."""
        fn = type(comp).STEP
        key = (id(fn), tuple(_type_key(a) for a in kargs))
        a = cls._ADDR.get(key)
        if a is None:
            ctype = kernel_args.container_type(kargs)
            try:
                ka = kernel_address(fn, kargs)
            except TypeError as exc:
                raise ContractError(f"{comp.name}: kernel {exc} (components/kernels.py: STEP returns its status)") from None
            try:
                ta = kernel_args.trampoline_address(ctype)
            except TypingError as exc:
                raise ContractError(f"{comp.name}: {exc}") from None
            a = cls._ADDR[key] = (ta, ka, ctype)
        return a

    def _back(self, LI, M, V, W, C, count):
        plan, eng = self.plan, self.sim.engine
        for j, link in enumerate(plan.links):
            n = plan.size[j]
            vo = int(LI[j, op.L_VOFF])
            cycles = None
            if link.window is not None:
                cw = int(LI[j, op.L_CW])
                c0 = int(LI[j, op.L_COFF])
                nout = int(W[j]["nout"])
                cycles = C[c0:c0 + nout * cw].reshape(nout, cw)
            _link_back(link, M[j], V[vo:vo + links.NV * n], W[j], cycles)
        for i, n in enumerate(plan.names):
            eng.steps_taken[n] += int(count[i])
            count[i] = 0

    def _observe(self, k0: int, k1: int, t_start: float) -> None:
        """Hand base steps k0 + 1 .. k1 (rows 0 .. k1 - k0 - 1) to the observers."""
        sim = self.sim
        h = self.h
        rows = k1 - k0
        sim.t = t_start + k1 * h
        for c, n in zip(self.plan.comps, self.plan.names):
            m = self.plan.mult[n]
            kf = (k1 // m) * m  # the end of its last window, as the generic do_step sets its time
            if kf > k0:
                hc = m * h
                c.time = (t_start + kf * h - hc) + hc
        if rows <= 0:
            return
        ks = np.arange(k0 + 1, k1 + 1)
        ts = t_start + ks * h  # the generic loop's t_start + k * h, element by element
        cols = self._columns(rows)
        for obs in sim.observers:
            obs.step_block(sim, ks, ts, cols)


def _type_key(v):
    """What numba's type of ``v`` depends on, read without numba: a key at least as fine as ``numba.typeof``
    (an array's dtype, dimensions, layout flags, writeability and alignment; a tuple's class and items; any other
    value through numba itself), ~10 times cheaper on the containers of a system of nine kernels (numba.typeof
    costs ~0.3 ms per kernel and interval, ~10 ms of a 0.7 s staggered run)."""
    if isinstance(v, np.ndarray):
        f = v.flags
        return (v.dtype.str, v.ndim, f.c_contiguous, f.f_contiguous, f.writeable, f.aligned)
    if isinstance(v, tuple):
        return (type(v), tuple(_type_key(x) for x in v))
    if type(v) is float:
        return float
    return numba.typeof(v)


def runner(sim, active, mult, step, stop):
    """A Runner for this thermo-mechanical interval, which choice.why_not found compilable, or the reason the
    compiled loop cannot run it after all (a str)."""
    comps = sim.system.components
    for ref in (stop.block_refs() if stop is not None else ()):
        comp, _, port = ref.partition(".")
        if comp not in mult or comps[comp].variable(port).type != "Real":
            return (f"the automatic schedule's steadiness test samples {ref}, not a Real output stepped in this "
                    "interval")
    for obs in sim.observers:
        for ref in obs.block_signals(sim):
            comp, _, port = ref.partition(".")
            if comp not in mult:
                return f"observer {type(obs).__name__} reads {ref}, not stepped in this interval"
            if comps[comp].variable(port).type != "Real":
                return f"observer {type(obs).__name__} reads {ref}, not a Real output"
    # the thermo-mechanical intervals of a run have the same plan (the hold's windows and hand-backs are set up
    # alike in each): its tables, flat port array, buffers and packed containers are built once per run and reused,
    # ~1.5 ms a staggered interval (plan, buffer pages, ports copied and containers packed anew)
    key = _plan_key(sim, mult)
    cached = _RUNNERS.get(sim)
    if cached is not None and cached[0] == key:
        cached[1].h = step
        return cached[1]
    plan = Plan(sim, active, mult)
    r = Runner(sim, plan, step)
    _RUNNERS[sim] = (key, r)
    return r


#: each simulation's runner and the key of its plan (kept while the simulation lives)
_RUNNERS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _plan_key(sim, mult) -> tuple:
    """What a :class:`Plan` is built from: the engine (a resumed run has another), the components stepped and
    their rates, each one's input, outgoing and watched links (their identities, modes and hand-off windows), the
    hold's hand-backs. Equal keys, equal plans (the runner keeps the plan's links alive, so no identity is reused)."""
    eng = sim.engine
    return (id(eng), tuple(eng.active), tuple(int(mult.get(n, 1)) for n in eng.active),
            tuple(id(sim.system.components[n]) for n in eng.active),
            tuple(tuple(map(id, eng.inputs_of(n))) for n in eng.active),
            tuple(tuple(map(id, eng.outgoing_of(n))) for n in eng.active),
            tuple(tuple(eng.watched_of(n)) for n in eng.active),
            tuple((link.mode, None if link.window is None else (tuple(link.window.ports), link.window.turns is None))
                  for link in eng.links),
            tuple(map(id, sim.hold.handbacks)))
