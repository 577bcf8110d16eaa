"""The compiled path of a thermo-mechanical interval (DESIGN "The master": two execution paths, one semantics).

When every component stepped in an interval offers a compiled kernel (components/kernels.py), the interval's
base steps run in one numba loop instead of the generic Python loop (algorithm.Engine.base_step), with the
same semantics, operation for operation:

* the Gauss-Seidel order and the multi-rate firing (component c fires at base step k when (k + 1) % n_c == 0,
  over [t_end - n_c h, t_end], t_end = t0 + (k + 1) h);
* each consumer's inputs gathered just before it fires, as algorithm._Link.value gives them: a copy of the
  producer's output, the mean or RMS over the consumer's window (fast -> slow), linear extrapolation to the
  middle (``linear``, slow -> fast) or to the end (``linear-end``) of the consumer's step; on the thermal-only
  hold's hand-backs, plus their restart offset after a thermal-only interval (hold.Restart);
* after each firing, as algorithm.Engine._fire: the step count, the finiteness of the outputs other components
  read, the links' bookkeeping (averages, extrapolation history, the ring buffers of the thermal-only hold);
* every ``check_every`` base steps the finiteness of all outputs;
* the same kernel functions as the components' generic do_step.

The loop for a system is generated as Python source (one function, the components' kernels called by name),
written into the cache folder (components/cache.py) and compiled by numba with ``cache=True``, so a second run
does not compile again. It runs in chunks: the signals the observers read are written into a buffer, one row per
base step, which the observers then consume (Observer.step_block); between chunks the components' state and
outputs are their own arrays (the kernels work on them in place), so checkpoints and observers see what the
generic path would show them. A kernel that needs Python for a step (the bearing's re-seating of its balls after
a thermal-only interval) or fails returns its status; the step is finished or the error raised in Python, as the
generic path would, and the loop resumes after that component.

Not compiled (the generic loop runs, and the reason is reported): a component without a kernel (FMUs, Python
plug-ins), Jacobi or iterative coupling, converted or non-Real links, inputs from components not stepped in the
interval, an observer without step_block, the automatic schedule's steadiness test.
"""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

from rotorcosim.components.cache import cache_dir
from rotorcosim.components.contract import ContractError
from rotorcosim.components.kernels import PYTHON, KernelComponent

from .algorithm import GaussSeidel, SimulationDiverged, _Link

ENGINES = ("auto", "python", "compiled")
#: base steps per compiled chunk (rows of the observers' buffer): ~1 ms of wall time between observer calls
CHUNK = 2048

# link bookkeeping, as numbers (algorithm._Link fields): meta = [has_acc, weight, has_prev, prev_t, has_cur,
# cur_t, then the hand-off window's (hold.HandOff): pos, count, has t_last, t_last, cycle sum, cycle count, last
# sample, samples per cycle, cycles written in this chunk, then a hand-back's restart offset (hold.Restart): its
# start and length (0: none)]; vec rows = [acc (or acc2), prev, last, the restart offset's delta]
(_HAS_ACC, _WEIGHT, _HAS_PREV, _PREV_T, _HAS_CUR, _CUR_T, _RPOS, _RCOUNT, _HAS_RT, _RT, _CSUM, _CN, _WLAST, _NCYC,
 _NOUT, _R0, _RLEN) = range(17)


class CompiledUnavailable(ContractError):
    """``--engine compiled`` asked for an interval the compiled path cannot run (the message says why)."""


def why_not(sim, active, mult, stop) -> str | None:
    """None when the interval can run compiled, else the reason it cannot."""
    comps = sim.system.components
    for n in active:
        c = comps[n]
        if not isinstance(c, KernelComponent) or c.STEP is None:
            return f"component {n} ({type(c).__name__}) has no compiled kernel"
        if not c.kernel_available():
            return f"component {n} has no compiled kernel in this phase"
    s = sim.engine.settings
    if type(sim.engine.algorithm) is not GaussSeidel or s.iterations != 1:
        return f"the {s.algorithm} algorithm with {s.iterations} iteration(s) (compiled: Gauss-Seidel, 1 iteration)"
    for link in sim.engine.links:
        d, src = link.con.dst_component, link.con.src_component
        if d not in mult:
            continue
        if src not in mult:
            return f"{link.con.src} -> {link.con.dst}: its producer does not step in this interval"
        if link.conv is not None or not link.real:
            return f"{link.con.src} -> {link.con.dst}: a converted or non-Real connection"
        if link.held is not None or link.frozen is not None:
            return f"{link.con.src} -> {link.con.dst}: held by the master"
    for link in sim.engine.links:
        if link.window is not None and link.con.src_component in mult:
            src = comps[link.con.src_component]
            if any(src.variable(p).type != "Real" for p in link.window.ports):
                return f"{link.con.src}: its hand-off window records non-Real inputs"
    for obs in sim.observers:
        if obs.block_signals(sim) is None:
            return f"observer {type(obs).__name__} has no step_block"
    if stop is not None:
        return "the automatic schedule's steadiness test samples every step in Python"
    return None


# -- code generation --------------------------------------------------------------------------------------
def _source(plan) -> str:
    """The numba source of the chunk loop of ``plan`` (see Plan)."""
    L = []
    w = L.append
    # numba's disk cache checks this file only, not the kernels it calls: their packages' sources are hashed
    # into it, so that an edited kernel gives another file (and a fresh compilation), never stale machine code
    w(f"# kernels' sources: {_kernel_sources_hash(tuple(sorted({fn.py_func.__module__ for fn in plan.kernels})))}")
    w("import math")
    w("import numpy as np")
    w("from numba import njit")
    for i, fn in enumerate(plan.kernels):
        w(f"from {fn.py_func.__module__} import {fn.py_func.__name__} as kernel_{i}")
    args = ["k0", "k1", "rstart", "t0", "h", "check_every", "count", "buf", "status"]
    for i in range(len(plan.names)):
        args += [f"s{i}", f"p{i}", f"u{i}", f"y{i}"]
    for j in range(len(plan.links)):
        args += [f"m{j}", f"v{j}", f"g{j}", f"c{j}"]
    w("")
    w("@njit(cache=True)")
    w(f"def run_chunk({', '.join(args)}):")
    w("    for k in range(k0, k1):")
    w("        t_end = t0 + (k + 1) * h")
    w("        resume = k == k0 and rstart >= 0")
    for i, name in enumerate(plan.names):
        m = plan.mult[name]
        w(f"        # {name}")
        w(f"        if (k + 1) % {m} == 0:")
        w(f"            hc = {m} * h")
        w("            t = t_end - hc")
        w(f"            if not (resume and {i} <= rstart):")
        for j, link in plan.inputs[i]:
            _gather(w, j, link, plan, " " * 16)
        w(f"                st = kernel_{i}(s{i}, p{i}, u{i}, y{i}, t, hc)")
        w("                if st != 0:")
        w(f"                    status[0] = st")
        w(f"                    status[1] = k")
        w(f"                    status[2] = {i}")
        w("                    return")
        w(f"            if not (resume and {i} < rstart):")
        w(f"                count[{i}] += 1")
        watch = plan.watch[i]
        if watch:
            w("                tot = 0.0")
            for port in watch:
                w(f"                for x in y{i}.{port}:")
                w("                    tot += x")
            w("                if not math.isfinite(tot):")
            w("                    status[0] = -1")
            w("                    status[1] = k")
            w(f"                    status[2] = {i}")
            w("                    return")
        if plan.outgoing[i]:
            w("                te = t + hc")
        for j, link in plan.outgoing[i]:
            _produced(w, j, link, plan, " " * 16, f"y{i}.{link.sport}")
    # the observers' row of this base step
    w("        row = k - k0")
    for ref, (i, port, off, size) in plan.observed.items():
        w(f"        for q in range({size}):")
        w(f"            buf[row, {off} + q] = y{i}.{port}[q]")
    w("        if (k + 1) % check_every == 0:")
    w("            tot = 0.0")
    for i in range(len(plan.names)):
        for port in plan.outputs[i]:
            w(f"            for x in y{i}.{port}:")
            w("                tot += x * 0.0")
    w("            if not math.isfinite(tot):")
    w("                status[0] = -2")
    w("                status[1] = k")
    w("                status[2] = -1")
    w("                return")
    w("    status[0] = 0")
    w("    status[1] = k1")
    w("    status[2] = -1")
    return "\n".join(L) + "\n"


@functools.cache
def _kernel_sources_hash(modules: tuple[str, ...]) -> str:
    # once per process: the code a process has loaded does not change, and reading and hashing the sources at
    # every thermo-mechanical interval was a fixed cost of each (three in a staggered run of rotorcosim compare)
    files = {Path(__file__).resolve()}
    for name in modules:
        files |= set(Path(sys.modules[name].__file__).resolve().parent.glob("*.py"))
    files.add(Path(sys.modules[KernelComponent.__module__].__file__).resolve())
    h = hashlib.sha256()
    for f in sorted(files):
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def _gather(w, j, link, plan, ind):
    """Inputs of a link as algorithm._Link.value gives them (frozen links do not occur in TM intervals)."""
    _gather_value(w, j, link, plan, ind)
    if j in plan.handbacks:
        # hold.Restart.offset at the consumer's step end (the generic loop passes t_end = t + hc)
        i_dst = plan.index[link.con.dst_component]
        w(f"{ind}if m{j}[{_RLEN}] > 0.0:")
        w(f"{ind}    rs = ((t + hc) - m{j}[{_R0}]) / m{j}[{_RLEN}]")
        w(f"{ind}    if rs < 1.0:")
        w(f"{ind}        if rs <= 0.0:")
        w(f"{ind}            rf = 1.0")
        w(f"{ind}        else:")
        w(f"{ind}            rf = 0.5 + 0.5 * math.cos(math.pi * rs)")
        w(f"{ind}        for q in range({plan.size[j]}):")
        w(f"{ind}            u{i_dst}.{link.dport}[q] = u{i_dst}.{link.dport}[q] + v{j}[3, q] * rf")


def _gather_value(w, j, link, plan, ind):
    i_src = plan.index[link.con.src_component]
    i_dst = plan.index[link.con.dst_component]
    src = f"y{i_src}.{link.sport}"
    dst = f"u{i_dst}.{link.dport}"
    n = plan.size[j]
    ex = link.con.extrapolation
    if link.mode == _Link.FAST_TO_SLOW and link.con.average != "last":
        w(f"{ind}if m{j}[{_WEIGHT}] > 0.0:")
        if link.con.average == "mean":
            w(f"{ind}    for q in range({n}):")
            w(f"{ind}        {dst}[q] = v{j}[0, q] / m{j}[{_WEIGHT}]")
        else:
            w(f"{ind}    for q in range({n}):")
            w(f"{ind}        {dst}[q] = math.sqrt(v{j}[0, q] / m{j}[{_WEIGHT}])")
        w(f"{ind}    m{j}[{_HAS_ACC}] = 0.0")
        w(f"{ind}    m{j}[{_WEIGHT}] = 0.0")
        w(f"{ind}else:")
        w(f"{ind}    for q in range({n}):")
        w(f"{ind}        {dst}[q] = {src}[q]")
        return
    extrap = (ex == "linear" and link.mode == _Link.SLOW_TO_FAST) or \
        (ex == "linear-end" and link.mode != _Link.FAST_TO_SLOW)
    if extrap:
        when = "t + 0.5 * hc" if ex == "linear" else "t + hc"
        w(f"{ind}if m{j}[{_HAS_PREV}] != 0.0 and m{j}[{_CUR_T}] > m{j}[{_PREV_T}]:")
        w(f"{ind}    c = ({when} - m{j}[{_CUR_T}]) / (m{j}[{_CUR_T}] - m{j}[{_PREV_T}])")
        w(f"{ind}    for q in range({n}):")
        w(f"{ind}        {dst}[q] = {src}[q] + ({src}[q] - v{j}[1, q]) * c")
        w(f"{ind}else:")
        w(f"{ind}    for q in range({n}):")
        w(f"{ind}        {dst}[q] = {src}[q]")
        return
    w(f"{ind}for q in range({n}):")
    w(f"{ind}    {dst}[q] = {src}[q]")


def _produced(w, j, link, plan, ind, y):
    """algorithm._Link.produced after the producer's step (hc, te = t + hc)."""
    n = plan.size[j]
    if link.mode == _Link.FAST_TO_SLOW:
        how = link.con.average
        if how in ("mean", "rms"):
            w(f"{ind}if m{j}[{_HAS_ACC}] == 0.0:")
            w(f"{ind}    for q in range({n}):")
            expr = f"{y}[q] * hc" if how == "mean" else f"{y}[q] * {y}[q] * hc"
            w(f"{ind}        v{j}[0, q] = {expr}")
            w(f"{ind}    m{j}[{_HAS_ACC}] = 1.0")
            w(f"{ind}else:")
            w(f"{ind}    for q in range({n}):")
            w(f"{ind}        v{j}[0, q] = v{j}[0, q] + {expr}")
        w(f"{ind}m{j}[{_WEIGHT}] += hc")
    elif link.mode == _Link.SLOW_TO_FAST or link.con.extrapolation == "linear-end":
        w(f"{ind}if m{j}[{_HAS_CUR}] != 0.0:")
        w(f"{ind}    for q in range({n}):")
        w(f"{ind}        v{j}[1, q] = v{j}[2, q]")
        w(f"{ind}    m{j}[{_HAS_PREV}] = 1.0")
        w(f"{ind}else:")
        w(f"{ind}    m{j}[{_HAS_PREV}] = 0.0")
        w(f"{ind}m{j}[{_PREV_T}] = m{j}[{_CUR_T}]")
        w(f"{ind}for q in range({n}):")
        w(f"{ind}    v{j}[2, q] = {y}[q]")
        w(f"{ind}m{j}[{_CUR_T}] = te")
        w(f"{ind}m{j}[{_HAS_CUR}] = 1.0")
    if link.window is not None:
        # hold.HandOff.record (a sample per producer step; no repeated steps here): the window ring and the
        # rotor-cycle means with the producer's thermal inputs at each cycle's end (rows of c{j}: mean, inputs)
        w(f"{ind}nr = g{j}.shape[0]")
        w(f"{ind}m{j}[{_HAS_RT}] = 1.0")
        w(f"{ind}m{j}[{_RT}] = te")
        w(f"{ind}pos = int(m{j}[{_RPOS}])")
        w(f"{ind}for q in range({n}):")
        w(f"{ind}    g{j}[pos, q] = {y}[q]")
        w(f"{ind}m{j}[{_RPOS}] = (pos + 1) % nr")
        w(f"{ind}m{j}[{_RCOUNT}] = min(m{j}[{_RCOUNT}] + 1, nr)")
        w(f"{ind}ys = {y}[0]")
        w(f"{ind}m{j}[{_WLAST}] = ys")
        w(f"{ind}m{j}[{_CSUM}] += ys")
        w(f"{ind}m{j}[{_CN}] += 1.0")
        w(f"{ind}if m{j}[{_CN}] == m{j}[{_NCYC}]:")
        w(f"{ind}    cr = int(m{j}[{_NOUT}])")
        w(f"{ind}    c{j}[cr, 0] = m{j}[{_CSUM}] / m{j}[{_CN}]")
        col = 1
        i_src = plan.index[link.con.src_component]
        for port, size in plan.window_ports[j]:
            w(f"{ind}    for q in range({size}):")
            w(f"{ind}        c{j}[cr, {col} + q] = u{i_src}.{port}[q]")
            col += size
        w(f"{ind}    m{j}[{_NOUT}] += 1.0")
        w(f"{ind}    m{j}[{_CSUM}] = 0.0")
        w(f"{ind}    m{j}[{_CN}] = 0.0")


_LOADED: dict[str, object] = {}


def _compile(source: str):
    """The run_chunk function of ``source``, from a module file named by its hash (numba caches next to it)."""
    key = hashlib.sha256(source.encode()).hexdigest()[:20]
    fn = _LOADED.get(key)
    if fn is not None:
        return fn
    folder = cache_dir("compiled")
    if folder is not None:
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError:
            folder = None
    if folder is None:  # caching off or not writable: compile in a temporary folder (each run compiles)
        folder = Path(tempfile.mkdtemp(prefix="rotorcosim-compiled-"))
    path = folder / f"loop_{key}.py"
    if not path.exists() or path.read_text() != source:
        tmp = path.with_name(path.name + ".part")
        tmp.write_text(source)
        tmp.replace(path)
    name = f"rotorcosim_compiled_loop_{key}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    _LOADED[key] = module.run_chunk
    return module.run_chunk


# -- the plan of an interval ----------------------------------------------------------------------------------
class Plan:
    """What the generated loop needs: components in order, their rates, the links into them, the watched and
    observed outputs."""

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

        self.inputs = [[(link_id(l), l) for l in eng._inputs[n]] for n in self.names]
        self.outgoing = [[(link_id(l), l) for l in eng._outgoing[n]] for n in self.names]
        # the thermal-only hold's hand-backs (a restart offset after a thermal-only interval): known from the
        # system, so that every thermo-mechanical interval of a run has the same loop source
        self.handbacks = {lid[id(l)] for l in sim.hold.handbacks if id(l) in lid}
        self.watch = [list(eng._watch[n]) for n in self.names]
        self.window_ports = [[(p, comps[l.con.src_component].variable(p).size) for p in l.window.ports]
                             if l.window is not None else [] for l in self.links]
        self.outputs = [[v.name for v in c.variables if v.causality == "output" and v.carried and v.type == "Real"]
                        for c in self.comps]
        # every Real output is buffered, whatever the observers read: the loop's source (and its compiled code,
        # cached on disk) then depends on the system only
        self.observed = {}
        off = 0
        for i, (n, c) in enumerate(zip(self.names, self.comps)):
            for port in self.outputs[i]:
                size = c.variable(port).size
                self.observed[f"{n}.{port}"] = (i, port, off, size)
                off += size
        self.width = max(1, off)
        self.source = _source(self)


def _link_arrays(link, n, max_cycles):
    m = np.zeros(17)
    v = np.zeros((4, n))
    if link.ramp is not None:
        m[_R0], m[_RLEN] = link.ramp.t0, link.ramp.length
        v[3] = link.ramp.delta
    acc = link.acc if link.con.average == "mean" else link.acc2
    if acc is not None:
        m[_HAS_ACC] = 1.0
        v[0] = acc
    m[_WEIGHT] = link.weight
    if link.prev is not None:
        m[_HAS_PREV] = 1.0
        v[1] = link.prev
        m[_PREV_T] = link.prev_t
    if link.cur_t is not None:
        m[_HAS_CUR] = 1.0
        m[_CUR_T] = link.cur_t
        v[2] = link._last
    ho = link.window
    if ho is not None:
        ring = ho.ring
        m[_RPOS], m[_RCOUNT] = ho.pos, ho.count
        if ho.t_last is not None:
            m[_HAS_RT], m[_RT] = 1.0, ho.t_last
        m[_CSUM], m[_CN], m[_WLAST], m[_NCYC] = ho.csum, ho.cn, ho._last, ho.n_cycle
        width = 1 + sum(np.ravel(link.src.u[p]).size for p in ho.ports)
        cycles = np.zeros((max_cycles, width))
    else:
        ring = np.zeros((1, n))
        cycles = np.zeros((1, 1))
    return [m, v, ring, cycles]


def _link_back(link, m, v, cycles):
    """The loop's bookkeeping back into the _Link and its hand-off window (thermal-only holds, checkpoints and
    the generic loop use them): prev is None exactly when prev_t is (algorithm._Link.produced), cur_t and _last
    likewise."""
    acc = v[0].copy() if m[_HAS_ACC] else None
    if link.con.average == "mean":
        link.acc = acc
    else:
        link.acc2 = acc
    link.weight = float(m[_WEIGHT])
    has_prev = bool(m[_HAS_PREV])
    link.prev = v[1].copy() if has_prev else None
    link.prev_t = float(m[_PREV_T]) if has_prev else None
    if m[_HAS_CUR]:
        link.cur_t = float(m[_CUR_T])
        link._last = v[2].copy()
    ho = link.window
    if ho is not None:
        ho.pos, ho.count = int(m[_RPOS]), int(m[_RCOUNT])
        ho.t_last = float(m[_RT]) if m[_HAS_RT] else None
        ho.csum, ho.cn, ho._last = float(m[_CSUM]), int(m[_CN]), float(m[_WLAST])
        for r in range(int(m[_NOUT])):
            ho.cycles.append((cycles[r, 1:].copy(), float(cycles[r, 0])))
        m[_NOUT] = 0.0


class Runner:
    """Runs base steps k..nsteps of one interval through the compiled loop."""

    def __init__(self, sim, plan: Plan, step: float):
        self.sim = sim
        self.plan = plan
        self.h = step
        self.fn = _compile(plan.source)
        # the observers' buffer and the refs each observer reads
        self.buf = np.zeros((CHUNK, plan.width))
        self.status = np.zeros(3, dtype=np.int64)

    def _columns(self, rows):
        b = self.buf[:rows]
        return {ref: b[:, off:off + size] for ref, (_, _, off, size) in self.plan.observed.items()}

    def run(self, k: int, nsteps: int, t_start: float) -> int:
        """Base steps k .. nsteps - 1; returns nsteps. ``self.k`` holds the steps completed when it raises."""
        sim, plan, h = self.sim, self.plan, self.h
        self.k = k
        eng = sim.engine
        comps = plan.comps
        for c, n in zip(comps, plan.names):
            c.kernel_prepare(plan.mult[n] * h)
            for key in list(c.u):  # each input its own array (the loop writes them in place)
                c.u[key] = np.array(c.u[key], dtype=float)
        args_links = []
        for link, n in zip(plan.links, plan.size):
            ncyc = link.window.n_cycle if link.window is not None else 1
            args_links += _link_arrays(link, n, CHUNK // ncyc + 2)
        count = np.zeros(len(comps), dtype=np.int64)
        check = int(eng.settings.check_every)
        r0 = -1
        while k < nsteps:
            k1 = min(nsteps, k + CHUNK)
            cargs = []
            for c in comps:
                cargs += list(c.kernel_args())
            self.fn(k, k1, r0, t_start, h, check, count, self.buf, self.status, *cargs, *args_links)
            code, kk, i = (int(x) for x in self.status)
            done = kk  # base steps completed
            self._back(args_links, count)
            self.k = done
            self._observe(k, done, t_start)
            k = done
            r0 = -1
            if code == 0:
                continue
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
                eng._diverged(name, t, t + hc)
            comp = comps[i]
            try:
                comp.kernel_status(code, t, hc)
            except SimulationDiverged:
                raise
            except Exception as exc:
                raise SimulationDiverged(f"{name} failed in do_step at t = {t:.9g} s: {exc}") from exc
            if code != PYTHON:
                raise SimulationDiverged(f"{name} failed in do_step at t = {t:.9g} s (kernel status {code})")
            comp.time = t + hc
            r0 = i  # resume after the component's step: its bookkeeping, then the next components
        sim.t = t_start + k * h
        return k

    def _back(self, args_links, count):
        plan, eng = self.plan, self.sim.engine
        for j, link in enumerate(plan.links):
            _link_back(link, args_links[4 * j], args_links[4 * j + 1], args_links[4 * j + 3])
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


def runner(sim, phase, active, mult, step, stop, choice: str):
    """A Runner for this interval, or None for the generic loop (the reason in sim.engine_note)."""
    if choice == "python" or phase != "TM":
        return None
    reason = why_not(sim, active, mult, stop)
    if reason is not None:
        return _refuse(sim, choice, reason)
    comps = sim.system.components
    for obs in sim.observers:
        for ref in obs.block_signals(sim):
            comp, _, port = ref.partition(".")
            if comp not in mult:
                return _refuse(sim, choice, f"observer {type(obs).__name__} reads {ref}, not stepped in this interval")
            if comps[comp].variable(port).type != "Real":
                return _refuse(sim, choice, f"observer {type(obs).__name__} reads {ref}, not a Real output")
    plan = Plan(sim, active, mult)
    return Runner(sim, plan, step)


def _refuse(sim, choice, reason):
    if choice == "compiled":
        raise CompiledUnavailable(f"--engine compiled: cannot compile the thermo-mechanical interval: {reason}")
    sim.engine_note = reason
    return None
