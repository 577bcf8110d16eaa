"""Compiled kernels of components: one step function shared by the generic and the compiled master paths.

A component that can offer a compiled kernel (numba) derives from :class:`KernelComponent` and provides

* ``STEP``: a ``numba.njit`` function ``step(s, p, u, y, t, h) -> status`` over four small typed containers
  (named tuples of numpy arrays and floats, fields named like the component's variables):
  ``s`` the state (arrays updated in place; the very arrays of ``self.state``), ``p`` constants and scratch,
  ``u`` the inputs (the arrays of ``self.u``, one field per input port), ``y`` the outputs (the arrays of
  ``self.y``, written in place, one field per output port);
* :meth:`kernel_args` building those four containers from the component's current dicts;
* :meth:`kernel_prepare` for what depends on the step size (the rotor's Newmark map, the thermal step matrices),
  done in Python once per step size;
* :meth:`kernel_status` turning a non-zero status into the component's own error, or finishing a step that needs
  Python (status :data:`PYTHON`: the kernel changed nothing and asks for it, e.g. the bearing's quasi-static
  re-seating of the balls after a thermal-only interval).

The generic ``do_step`` calls the same ``STEP`` (so both master paths do the same arithmetic: compiled and
generic runs are equal by construction); the master's compiled loop (master/compiled/runner.py) calls ``STEP`` from a
compiled loop over a whole thermo-mechanical interval. Outputs are written in place: the master copies what it
keeps (links, rings, observers), so an output array is never held across a step.
"""
from __future__ import annotations

import hashlib
import re
from collections import namedtuple

import numpy as np

from .contract import Component

#: kernel status codes: 0 done; PYTHON: nothing changed, run the step through kernel_status; >= 2: component errors;
#: EVENT: the step is done and one of the component's event indicators changed sign over it (the compiled loop
#: stops there and the master locates the event, master/core/events.py; the generic loop reads ``indicators()``)
OK, PYTHON, EVENT = 0, 1, -3

#: every port tuple type made so far, (class name, kind, port names) -> type (sent to the ahead-of-time compiler)
PORT_TUPLES: dict[tuple, type] = {}


def port_tuple(cls_name: str, kind: str, names: tuple[str, ...]) -> type:
    """The named tuple type of a component class's input or output ports (one per class and kind).

    Made a global of this module, so that it pickles by reference: numba's on-disk cache compares the types of a
    new call with the pickled ones, and a class pickled by value would never match (a recompilation every run)."""
    key = (cls_name, kind, names)
    t = PORT_TUPLES.get(key)
    if t is None:
        name = f"{cls_name}{kind}"
        if name in globals():  # another class of that name with other ports
            name += "_" + hashlib.sha256(repr(names).encode()).hexdigest()[:8]
        t = namedtuple(name, names)
        t.__module__ = __name__
        globals()[name] = t
        PORT_TUPLES[key] = t
    return t


# -- an inner function called by address ---------------------------------------------------------------------
# numba compiles each njit function into its own module, and a caller that calls it by name links that module into
# its own and optimises and machine-codes all of it again: a kernel over a chain of four functions compiles the
# innermost four times (on a fresh machine's first run most of the compile CPU). A large inner function that a
# kernel calls through its address instead (numba_internals.by_address / address_of / call_at) is compiled once,
# on its own (and can be compiled by the helper process of a fresh machine, master/compiled/ahead.py: its
# signature is declared). They live with numba's other internals; the names stay importable from here.
_BY_ADDRESS_NAMES = ("by_address", "address_of", "call_at")


_STALE: dict[str, type] = {}


def __getattr__(name):
    # imported on first use: this module (KernelComponent, the status codes) does not import numba
    if name in _BY_ADDRESS_NAMES:
        from . import numba_internals

        return getattr(numba_internals, name)
    if re.fullmatch(r"[A-Za-z]\w*(Inputs|Outputs)(_[0-9a-f]+)?", name):
        # a port tuple that a numba cache index names but this process has not made (numba unpickles a kernel's
        # whole index, every signature in it, before it reads any: e.g. the rotor's named ports of an older
        # version): a stand-in class that no live type equals, so that entry is skipped, not an error
        t = _STALE.get(name)
        if t is None:
            t = _STALE[name] = namedtuple(name, ())
            t.__module__ = __name__
        return t
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class KernelComponent(Component):
    """A native component whose time step is a compiled kernel (module docstring)."""

    #: the njit step function (set by subclasses, wrapped in staticmethod)
    STEP = None
    #: True when ``STEP`` returns ``EVENT`` whenever one of the component's event indicators changes sign over the
    #: step (the compiled loop then runs it and stops at its events); a component with event indicators whose
    #: kernel does not say so runs in the generic loop
    KERNEL_EVENTS = False

    def _ports(self, causality: str) -> tuple[str, ...]:
        return tuple(v.name for v in self.variables if v.causality == causality and v.carried)

    def kernel_ports(self):
        """(input tuple type, output tuple type, input names, output names), built once per instance."""
        kp = self.__dict__.get("_kernel_ports")
        if kp is None:
            ins, outs = self._ports("input"), self._ports("output")
            name = type(self).__name__
            kp = (port_tuple(name, "Inputs", ins), port_tuple(name, "Outputs", outs), ins, outs)
            self._kernel_ports = kp
        return kp

    def kernel_io(self):
        U, Y, ins, outs = self.kernel_ports()
        u, y = self.u, self.y
        return U(*[u[n] for n in ins]), Y(*[y[n] for n in outs])

    # -- to provide ----------------------------------------------------------------------------------
    def kernel_state(self):
        """The state container ``s`` over the arrays of ``self.state``."""
        raise NotImplementedError

    def kernel_params(self):
        """The constants and scratch container ``p`` (after :meth:`kernel_prepare`)."""
        raise NotImplementedError

    def kernel_prepare(self, h: float) -> None:
        """Make ``kernel_params`` valid for steps of size ``h`` (nothing by default)."""

    def kernel_status(self, status: int, t: float, h: float) -> None:
        """Handle a non-zero status of ``STEP`` for the step from t to t + h: raise the component's error, or
        finish the step in Python (status PYTHON)."""
        raise RuntimeError(f"{self.name}: kernel status {status} at t = {t + h:.9g} s")

    def set_parameter(self, name, value):
        super().set_parameter(name, value)
        self._kernel_h = None          # constants taken from the parameters are rebuilt at the next step

    # -- what the master uses -------------------------------------------------------------------------
    def kernel_available(self) -> bool:
        """True when the next steps (this phase, these parameters) are the kernel's."""
        return True

    def kernel_args(self):
        u, y = self.kernel_io()
        return self.kernel_state(), self.kernel_params(), u, y

    def kernel_step(self, t: float, h: float) -> None:
        """One step through the kernel (the generic do_step of kernel components)."""
        self.kernel_prepare(h)
        s, p, u, y = self.kernel_args()
        status = self.STEP(s, p, u, y, t, h)
        if status and status != EVENT:
            self.kernel_status(status, t, h)
        self.time = t + h

    def do_step(self, t, h):
        self.kernel_step(t, h)


class PositionalKernelComponent(KernelComponent):
    """A kernel component whose ports follow a data file (the rotor's and the airframe's follow the engine file):
    its kernel reads them by position through offset tables, in plain tuples."""

    def kernel_ports(self):
        """Plain tuples, not named ones: numba's on-disk cache of a kernel holds every signature it was compiled
        for in one index, which a process must unpickle whole: a named tuple class of another engine's ports would
        not exist there. The kernel reads the ports by position (its offset tables), so a plain tuple carries all
        it needs; its type is keyed by the ports' count."""
        kp = self.__dict__.get("_kernel_ports")
        if kp is None:
            kp = (tuple, tuple, self._ports("input"), self._ports("output"))
            self._kernel_ports = kp
        return kp

    def kernel_io(self):
        # one array type for all ports (the kernel indexes them at run time): inputs made contiguous (a no-op for
        # the master's arrays); outputs are the component's own contiguous arrays, written in place
        _, _, ins, outs = self.kernel_ports()
        u, y = self.u, self.y
        return tuple(np.ascontiguousarray(u[n]) for n in ins), tuple(y[n] for n in outs)
