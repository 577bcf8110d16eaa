"""The generic pythonfmu slave that puts one rotorcosim component behind the FMI 2.0 co-simulation boundary.

This file is *copied* into every exported FMU's resources under a module name unique to that FMU (two FMUs
loaded in one Python process must not share a module in ``sys.modules``), next to a JSON file of the same
stem that says which component class to build, from which bundled private package, with which parameters and
which declared variables. It must therefore import nothing from rotorcosim: only the standard library,
numpy, pythonfmu and the bundled package (named in the JSON).

Mapping of the contract onto FMI 2.0:

* a vector port ``X`` of size n becomes the scalars ``X[1]`` .. ``X[n]`` (1-based, structured naming);
  a size-1 port keeps its plain name;
* parameters are ``causality="parameter"``, ``variability="fixed"``: they may be set between instantiation
  and the end of initialisation; the component is built at ``exit_initialization_mode`` from the parameters
  *set* (those baked in at export plus those set through FMI), so that a component which derives defaults
  from other parameters (the damper's Table 3 geometry) behaves exactly as it does natively;
* inputs are held over ``do_step`` and pushed with ``set_inputs``; outputs are read from ``component.y``;
* ``get/set FMU state`` snapshots the component's own ``get_state()`` plus the slave's copies of the
  inputs/outputs (the object stays in memory: no serialisation, ``canSerializeFMUstate`` is false);
* a failure inside the component fails the FMI call, and its own message is kept in a local String variable
  (named in the JSON and the vendor annotation) that the importer reads to report it;
* the staggered schedule's phase crosses as two extra Integer variables named in the JSON (and in the
  vendor annotation): an input (0 = thermo-mechanical, 1 = thermal-only) whose every setting calls the
  component's ``enter_phase``, and an output, the phases the component takes part in after its set-up
  (bit 1: TM, bit 2: TO, bit 4: ``holds_state_in_TO``), since a component may decide them from its
  parameters. Other tools leave the input at 0: the component then always runs thermo-mechanically.
"""
import atexit
import contextlib
import copy
import ctypes
import glob
import importlib
import json
import os
import sys

import numpy as np
from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real, String

try:  # one BLAS thread, as in rotorcosim's own runs (master/core/threads.py): the host tool may run BLAS multi-threaded,
    # which sums in another order and changes the last digits of a result
    from threadpoolctl import ThreadpoolController
except ImportError:  # a host Python without it: the component runs with the host's BLAS threads
    ThreadpoolController = None

#: the pythonfmu binaries (one per FMU extracted in this process) whose interpreter state is released at exit
_RELEASED = set()


def _release_at_exit(resources):
    """Have the interpreter release pythonfmu's global interpreter state of this FMU's binary at exit, while the
    binary is still whole.

    Why: pythonfmu 0.7's binary keeps that state in a global ``std::shared_ptr`` and releases it twice when the
    process ends with the binary still loaded, which it always is (its C++ template statics are
    ``STB_GNU_UNIQUE`` symbols, so glibc never unloads it, whatever the host's dlclose): first the C++ static
    destructor (an ``atexit`` entry), then its ``__attribute__((destructor))``, which assigns nullptr to the
    destroyed pointer and so releases its freed control block again (valgrind: "Invalid read ... in
    finalizePythonInterpreter ... inside a block free'd by __run_exit_handlers"). When the freed block happens
    to read as a count of 1, the block is freed twice: "corrupted double-linked list" or a segfault at exit,
    likelier with each FMU loaded (each extraction is its own copy of the binary). Calling the binary's own
    ``finalizePythonInterpreter`` once before that (a Python ``atexit`` runs before the C library's) empties
    the pointer cleanly; both later releases then find nothing to release. Instances still alive keep their own
    reference, so the call is harmless whenever it runs. Linux only: elsewhere the binary unloads in order."""
    if not sys.platform.startswith("linux"):
        return
    folder = os.path.join(os.path.dirname(os.path.abspath(resources)), "binaries", "linux64")
    for lib in glob.glob(os.path.join(folder, "*.so")):
        if lib in _RELEASED:
            continue
        try:   # the copy the host loaded (RTLD_NOLOAD: never a second one)
            release = ctypes.CDLL(lib, mode=os.RTLD_NOLOAD | os.RTLD_NOW).finalizePythonInterpreter
        except (OSError, AttributeError):   # not loaded under this name, or another wrapper: nothing to do
            continue
        release.argtypes, release.restype = [], None
        _RELEASED.add(lib)
        atexit.register(release)


_TYPES = {"Real": Real, "Integer": Integer, "Boolean": Boolean, "String": String}
_CONVERT = {"Real": float, "Integer": int, "Boolean": bool, "String": str}


def _scalar_names(name, size):
    return [name] if size == 1 else [f"{name}[{i + 1}]" for i in range(size)]


class RotorcosimSlave(Fmi2Slave):
    """One rotorcosim component as a pythonfmu co-simulation slave (configured by the JSON beside it)."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        _release_at_exit(self.resources)
        with open(os.path.join(self.resources, __name__ + ".json"), encoding="utf-8") as f:
            cfg = json.load(f)
        self._cfg = cfg
        self.modelName = cfg["model_identifier"]
        self.description = cfg["description"]
        self.author = "rotorcosim"
        self.version = cfg["version"]
        self._component = None
        self._threads = None    # the BLAS/OpenMP pools limited to one thread, known after the component's import
        self._t0 = 0.0
        self._explicit = set(cfg["parameters"])        # parameters passed to the constructor
        self._par, self._u, self._y, self._type = {}, {}, {}, {}
        self._real = {}     # value reference -> (store, port, index): the fast path of get_real/set_real
        for v in cfg["variables"]:
            name, size, kind = v["name"], v["size"], v["type"]
            self._type[name] = kind
            if v["causality"] == "parameter":
                start = cfg["parameters"].get(name, v["start"])
                self._par[name] = (list(np.broadcast_to(np.asarray(start), (size,)).tolist())
                                   if kind != "String" else [start])
                store = "_par"
            elif v["causality"] == "input":
                self._u[name] = np.broadcast_to(np.asarray(v["start"], dtype=float), (size,)).copy()
                store = "_u"
            else:
                self._y[name] = np.broadcast_to(np.asarray(v["start"], dtype=float), (size,)).copy()
                store = "_y"
            for i, scalar in enumerate(_scalar_names(name, size)):
                var = self._make(v, scalar, store, name, i)
                self.register_variable(var, nested=False)
                if kind == "Real":
                    self._real[var.value_reference] = (store, name, i)
        self._phase = 0
        self.register_variable(Integer(cfg["phase_input"], causality=Fmi2Causality.input,
                                       variability=Fmi2Variability.discrete, description=(
                                           "rotorcosim schedule phase: 0 thermo-mechanical, 1 thermal-only"),
                                       getter=lambda: self._phase, setter=self._enter_phase), nested=False)
        self._error = ""
        self.register_variable(String(cfg["error_variable"], causality=Fmi2Causality.local,
                                      variability=Fmi2Variability.discrete, description=(
                                          "the last error of the component (its own message)"),
                                      getter=lambda: self._error), nested=False)
        self.register_variable(Integer(cfg["phases_output"], causality=Fmi2Causality.output,
                                       variability=Fmi2Variability.discrete, description=(
                                           "phases taken part in: 1 TM + 2 TO + 4 holds its state in TO"),
                                       getter=self._phase_bits), nested=False)

    def _enter_phase(self, value):
        self._phase = int(value)
        if self._component is not None:
            self._component.enter_phase("TO" if self._phase else "TM")

    def _phase_bits(self):
        c = self._component
        phases = c.phases if c is not None else self._cfg["phases"]
        holds = c.holds_state_in_TO if c is not None else False
        return ("TM" in phases) * 1 + ("TO" in phases) * 2 + bool(holds) * 4

    def _make(self, v, scalar, store, name, i):
        # the getter/setter look the store up by attribute name each time: set_fmu_state replaces the dicts
        cls = _TYPES[v["type"]]
        convert = _CONVERT[v["type"]]
        causality = getattr(Fmi2Causality, v["causality"])
        if v["causality"] == "parameter":
            variability = Fmi2Variability.fixed

            def setter(value):
                getattr(self, store)[name][i] = convert(value)
                self._explicit.add(name)
        elif v["causality"] == "input":
            variability = Fmi2Variability.continuous

            def setter(value):
                getattr(self, store)[name][i] = float(value)
        else:
            variability = Fmi2Variability.continuous
            setter = None

        def getter():
            return convert(getattr(self, store)[name][i])

        return cls(scalar, causality=causality, variability=variability, description=v["description"] or None,
                   getter=getter, setter=setter)

    # -- Real values: the hot path of every communication step (pythonfmu's generic version calls a
    #    getter closure and an isinstance check per scalar; this reads the port arrays directly) ------------
    def get_real(self, vrs):
        real = self._real
        try:
            return [float(getattr(self, a)[n][i]) for a, n, i in map(real.__getitem__, vrs)]
        except KeyError:
            return super().get_real(vrs)   # not a Real: pythonfmu's error message

    def set_real(self, vrs, values):
        real = self._real
        for vr, value in zip(vrs, values):
            ref = real.get(vr)
            if ref is None or ref[0] == "_y":
                super().set_real([vr], [value])   # an output or not a Real: pythonfmu's handling
                continue
            a, n, i = ref
            getattr(self, a)[n][i] = float(value)
            if a == "_par":
                self._explicit.add(n)

    # -- the FMI calls ----------------------------------------------------------------------------------
    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self._t0 = float(start_time)

    def _guard(self, call, *args):
        """Run ``call``; a failure is *not* raised into pythonfmu (its native exception path corrupts the
        interpreter's reference counts: crashes later, in the garbage collector), but kept as the component's
        own message for the importer, and the call reports failure by its return value."""
        try:
            with (self._threads.limit(limits=1) if self._threads is not None else contextlib.nullcontext()):
                call(*args)
            return True
        except Exception as exc:  # noqa: BLE001 - every failure of the component becomes an FMI error
            self._error = f"{type(exc).__name__}: {exc}"
            return False

    def exit_initialization_mode(self):
        # pythonfmu ignores this call's return value: a failed set-up leaves no component, the importer reads
        # the error variable, and any later doStep fails
        self._guard(self._initialise)

    def _initialise(self):
        pkg = importlib.import_module(self._cfg["package"])
        module = importlib.import_module(pkg.__name__ + "." + self._cfg["module"])
        cls = getattr(module, self._cfg["class"])
        if ThreadpoolController is not None:
            # the libraries the component's module loaded are known now (29 us a step to enter, measured)
            self._threads = ThreadpoolController()
            with self._threads.limit(limits=1):
                self._build(cls)
        else:
            self._build(cls)

    def _build(self, cls):
        params = {}
        for v in self._cfg["variables"]:
            n = v["name"]
            if v["causality"] == "parameter" and n in self._explicit:
                params[n] = self._par[n][0] if v["size"] == 1 else list(self._par[n])
        # the FMI instance name (the importing scenario's component name) names the component in its messages
        comp = cls(self.instance_name or self._cfg["instance_name"], params)
        comp.set_inputs({k: v.copy() for k, v in self._u.items()})
        comp.setup(self._t0)
        comp.set_inputs({k: v.copy() for k, v in self._u.items()})   # setup may reset inputs to their starts
        self._component = comp
        self._read_outputs()

    def _read_outputs(self):
        y = self._component.get_outputs()
        self._error = ""
        for name in self._y:
            self._y[name] = np.array(y[name], dtype=float).reshape(-1)

    def do_step(self, current_time, step_size):
        return self._guard(self._step, current_time, step_size)

    def _step(self, current_time, step_size):
        comp = self._component
        if comp is None:
            raise RuntimeError(self._error or "the component was not set up (exitInitializationMode failed?)")
        comp.set_inputs(self._u)
        comp.do_step(float(current_time), float(step_size))
        self._read_outputs()
        return True

    def terminate(self):
        if self._component is not None:
            self._component.terminate()

    # -- FMU state: the component's own snapshot plus the slave's port copies ---------------------------
    def _get_fmu_state(self):
        return {
            "component": None if self._component is None else self._component.get_state(),
            "u": copy.deepcopy(self._u),
            "y": copy.deepcopy(self._y),
            "par": copy.deepcopy(self._par),
            "explicit": set(self._explicit),
        }

    def _set_fmu_state(self, state):
        if (state["component"] is None) != (self._component is None):
            raise RuntimeError("FMU state taken before initialisation cannot be restored after it (or back)")
        if self._component is not None:
            self._component.set_state(state["component"])
        self._u = copy.deepcopy(state["u"])
        self._y = copy.deepcopy(state["y"])
        self._par = copy.deepcopy(state["par"])
        self._explicit = set(state["explicit"])
