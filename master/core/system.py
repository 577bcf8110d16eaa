"""A system: components plus connections, checked when built.

Checks (each error names the ports): unknown component or port, causality (an output drives an input), vector
size, value type and unit (conversions.py: what converts implicitly, what needs the connection's ``convert`` or
``unit``, what is refused), an input driven twice, an input left unconnected (unless the scenario gives it a
constant value, checked against the input's type and range; Binary and Clock inputs, which carry no value, may
stay unconnected). An output driving nothing is fine.

An input that declares a default (``Variable.has_default``: an imported FMU's input with a start value, as fmpy,
Ecos and OMSimulator treat it; a native input only when its component says so) may stay unconnected and keeps
its start value; ``unconnected_inputs = "error"`` refuses those too. :attr:`System.defaulted` lists them.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np

from rotorcosim.components.contract import Component, ContractError
from rotorcosim.components.value_types import check_value

from rotorcosim.master.core.conversions import ConversionError, link_conversion


#: what a slower input sees of a faster output over its step (``average``), and what a thermal-only interval
#: holds of a signal over the hand-off window (``hold``): the same three statistics
STATISTICS = ("mean", "rms", "last")
AVERAGES = HOLDS = STATISTICS
EXTRAPOLATIONS = ("hold", "linear", "linear-end")
#: what an unconnected input that declares a default does: keep its start value, or stop the build
UNCONNECTED_INPUTS = ("start", "error")


class SystemError_(ContractError):
    """A system that cannot be built: the message names the offending ports."""


@dataclass
class Connection:
    """``src`` output drives ``dst`` input; both written ``component.port``.

    ``average``: how a slower consumer sees a faster producer (mean or RMS over its step, or the last value);
    ``extrapolation``: how a faster consumer sees a slower producer (hold, or linear to the middle of the
    consumer's step); ``linear-end`` extrapolates linearly to the END of the consumer's step, for same-rate links
    too: a consumer that enforces equilibrium at the step end with the held input (Newmark) then sees the
    producer's force at the right time, which lifts the coupling lag from first to second order;
    ``hold``: what replaces a frozen producer's output in a thermal-only interval (None: the schedule default);
    averaging, extrapolation and the held statistic apply to Real signals only (others are held as they are);
    ``convert``: the explicit type conversion of the connection (conversions.py), e.g. ``"round"`` for a Real
    output into an Integer input; ``unit``: the unit of the side that has none (conversions.py).
    """

    src: str
    dst: str
    average: str = "mean"
    extrapolation: str = "hold"
    hold: str | None = None
    convert: str | None = None
    unit: str | None = None
    origin: str | None = None  #: the scenario file that brought it (named in errors)

    def __post_init__(self):
        for label, value, allowed in (("average", self.average, AVERAGES),
                                      ("extrapolation", self.extrapolation, EXTRAPOLATIONS)):
            if value not in allowed:
                raise SystemError_(f"connection {self.src} -> {self.dst}: {label} {value!r} not in {allowed}")
        if self.hold is not None and self.hold not in HOLDS:
            raise SystemError_(f"connection {self.src} -> {self.dst}: hold {self.hold!r} not in {HOLDS}")

    @property
    def src_component(self) -> str:
        """The producing component's name (``src`` before the dot)."""
        return split_port(self.src)[0]

    @property
    def src_port(self) -> str:
        """The output's name (``src`` after the dot)."""
        return split_port(self.src)[1]

    @property
    def dst_component(self) -> str:
        """The consuming component's name (``dst`` before the dot)."""
        return split_port(self.dst)[0]

    @property
    def dst_port(self) -> str:
        """The input's name (``dst`` after the dot)."""
        return split_port(self.dst)[1]


def split_port(ref: str) -> tuple[str, str]:
    """``"component.port"`` -> ``("component", "port")`` (the port may contain dots); an error otherwise.

    >>> split_port("damperA.F_journal")
    ('damperA', 'F_journal')
    """
    comp, dot, port = str(ref).partition(".")
    if not dot or not comp or not port:
        raise SystemError_(f"port reference {ref!r} must be written 'component.port'")
    return comp, port


@dataclass
class System:
    """Components and the connections between them, checked when built (see the module's docstring).

    Parameters: ``components`` (instance name -> :class:`~rotorcosim.components.contract.Component`);
    ``connections`` (:class:`Connection`, each output -> input); ``inputs``: constant values of inputs no
    connection drives (``"component.port"`` -> value in the input's unit, a scalar filling a vector input);
    ``origins``: component name -> the scenario file that chose it, named in errors; ``unconnected_inputs``
    (UNCONNECTED_INPUTS): ``"start"`` lets an input that declares a default stay unconnected at its start value
    (listed in :attr:`defaulted` after the check), ``"error"`` refuses every unconnected input. A scenario
    builds its system with :func:`rotorcosim.master.scenario.build.build_system`;
    :class:`rotorcosim.master.simulation.Simulation` runs one.

    >>> from rotorcosim.components.registry import create
    >>> comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
    ...          "m2": create("testing.spring", "m2", {"m": 2.0, "k": 30.0, "kc": 100.0})}
    >>> system = System(comps, [Connection("m1.x", "m2.x_in"), Connection("m1.v", "m2.v_in"),
    ...                         Connection("m2.F", "m1.F")])
    >>> [c.src for c in system.connections_into("m1")]
    ['m2.F']
    """
    components: dict[str, Component]
    connections: list[Connection]
    inputs: dict[str, np.ndarray] = field(default_factory=dict)
    #: component name -> the scenario file that chose its implementation (named in errors)
    origins: dict[str, str] = field(default_factory=dict)
    unconnected_inputs: str = "start"

    def __post_init__(self):
        if self.unconnected_inputs not in UNCONNECTED_INPUTS:
            raise SystemError_(f"unconnected_inputs {self.unconnected_inputs!r} not in {UNCONNECTED_INPUTS}")
        self.check()

    def component(self, name: str) -> Component:
        """The component ``name``; an error listing the components otherwise."""
        try:
            return self.components[name]
        except KeyError:
            raise SystemError_(f"unknown component {name!r}; components: {', '.join(self.components)}") from None

    def port(self, ref: str, causality: str):
        """The variable of port ``ref`` (``"comp.port"``), which must be of ``causality`` (``"input"``,
        ``"output"``); a SystemError naming the component's ports of that causality otherwise."""
        comp, port = split_port(ref)
        c = self.component(comp)
        try:
            v = c.variable(port)
        except ContractError:
            known = ", ".join(x.name for x in c.variables if x.causality == causality)
            raise SystemError_(f"{ref}: component {comp!r} ({c!r}) has no {causality} {port!r} "
                               f"(its {causality}s: {known})") from None
        if v.causality != causality:
            art = "an" if v.causality[0] in "aeiou" else "a"
            raise SystemError_(f"{ref} is {art} {v.causality} of component {comp!r} ({type(c).__name__}), used as "
                               f"an {causality}")
        return v

    def check(self) -> None:
        """Check the connections and the constant inputs (run when the system is built); the first problem
        raises :class:`SystemError_` naming the ports (and the scenario file that brought a connection)."""
        #: input reference -> the conversion its connection applies (only links that need one)
        self.converters: dict[str, object] = {}
        driven: dict[str, str] = {}
        for con in self.connections:
            try:
                self._check_connection(con, driven)
            except SystemError_ as exc:
                if con.origin is None:
                    raise
                raise SystemError_(f"{exc} (connection from {con.origin})") from None
            driven[con.dst] = con.src
        for ref, value in list(self.inputs.items()):
            inp = self.port(ref, "input")
            if ref in driven:
                raise SystemError_(f"{ref} has a constant value and is also driven by {driven[ref]}")
            items = list(value) if isinstance(value, (list, tuple, np.ndarray)) else [value]
            if len(items) == 1 and inp.size > 1:
                items = items * inp.size   # a scalar constant fills a vector input
            try:
                self.inputs[ref] = check_value(inp, items, f"constant input {ref}")
            except ContractError as exc:
                raise SystemError_(str(exc)) from None
        #: unconnected inputs that keep their declared start values: reference -> value
        self.defaulted: dict[str, np.ndarray] = {}
        missing = []
        for name, c in self.components.items():
            for v in c.variables:
                ref = f"{name}.{v.name}"
                if v.causality != "input" or not v.carried or ref in driven or ref in self.inputs:
                    continue
                if v.has_default and self.unconnected_inputs == "start":
                    self.defaulted[ref] = v.start_array()
                else:
                    missing.append(ref)
        if missing:
            where = sorted({self.origins[m.partition(".")[0]] for m in missing if m.partition(".")[0] in self.origins})
            if self.unconnected_inputs == "error":
                why = 'unconnected_inputs = "error": connect them or give a constant under [inputs]'
            else:
                why = ("connect them or give a constant under [inputs]; they declare no default to keep (an FMU "
                       "input's is its start value)")
            raise SystemError_(f"inputs left unconnected ({why}): "
                               + ", ".join(missing) + (f" (components from {', '.join(where)})" if where else ""))

    def _check_connection(self, con: Connection, driven: dict[str, str]) -> None:
        out = self.port(con.src, "output")
        inp = self.port(con.dst, "input")
        if out.size != inp.size:
            raise SystemError_(f"{con.src} (size {out.size}) -> {con.dst} (size {inp.size}): sizes differ")
        try:
            fn = link_conversion(out, inp, con.convert, con.unit, f"{con.src} -> {con.dst}")
        except ConversionError as exc:
            raise SystemError_(str(exc)) from None
        if fn is not None:
            self.converters[con.dst] = fn
        if con.dst in driven:
            raise SystemError_(f"{con.dst} is driven twice: by {driven[con.dst]} and by {con.src}")

    def connections_into(self, component: str) -> list[Connection]:
        """The connections that drive inputs of ``component``."""
        return [c for c in self.connections if c.dst_component == component]


def build(components: Mapping[str, Component], connections: Sequence[Connection],
          inputs: Mapping[str, Sequence[float]] | None = None, unconnected_inputs: str = "start") -> System:
    """A checked :class:`System` of ``components``, ``connections`` and constant ``inputs`` (copied)."""
    return System(dict(components), list(connections), dict(inputs or {}), unconnected_inputs=unconnected_inputs)


def defaulted_line(defaulted: Mapping[str, np.ndarray]) -> str:
    """One line listing the unconnected inputs that keep their start values (what a run prints on stderr).

    >>> defaulted_line({"f.u": np.array([0.5]), "f.s": np.array(["on"], dtype=object)})
    "inputs left unconnected keep their start values: f.u = 0.5, f.s = 'on'"
    """
    def text(value: np.ndarray) -> str:
        items = [x.item() if isinstance(x, np.generic) else x for x in value]
        return repr(items[0]) if len(items) == 1 else "[" + ", ".join(repr(x) for x in items) + "]"
    return "inputs left unconnected keep their start values: " + ", ".join(
        f"{ref} = {text(v)}" for ref, v in defaulted.items())
