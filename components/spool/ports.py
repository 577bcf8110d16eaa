"""A spool's torque inputs: one drag torque per co-simulated bearing on it, one friction torque per rub ring.

The ports are ``T_drag1`` .. ``T_dragN`` and ``T_rub1`` .. ``T_rubM`` [N m], each opposing the spin, N the number
of ``bearing<ID>`` and M of ``rubring<ID>`` entries of the engine file's ``[attach]`` whose node is on the spool
(``node = [spool, node]``, components/rotor/attach.py), in [attach] order; at least two of each (a spool with fewer
sets the others to 0, as does a spool with no engine file or a single-shaft model file). The spool sums them, so
which bearing feeds which drag port is free; every port must be connected or given a value (a bearing whose drag
is left out of its spool's balance would be a torque the run forgets).

Example (an engine with bearings "1", "2", "3" on spool ``rotor``)::

    >>> counts = torque_layout({"attach": {"bearing1": {"node": ["rotor", 2]}, "bearing2": {"node": ["rotor", 7]},
    ...                                    "bearing3": {"node": ["rotor", 12]}}, "spool": {"rotor": {}}}, "rotor")
    >>> counts
    Layout(bearings=('1', '2', '3'), rubrings=())
    >>> [v.name for v in torque_variables(counts)]
    ['T_drag1', 'T_drag2', 'T_drag3', 'T_rub1', 'T_rub2']
"""
from __future__ import annotations

from ..contract import Variable
from ..rotor import attach

#: the torque ports of each kind a spool always has
MIN_PORTS = 2
#: the input port prefixes, by kind (the spool's kernel sums the drag ports first, then the rub ports)
DRAG, RUB = "T_drag", "T_rub"


def torque_layout(data: dict, spool: str) -> attach.Layout | None:
    """The bearings and rub rings on spool ``spool`` of an engine file's data; None for a file whose spools or
    [attach] say nothing of it (a single-shaft model file, a spool it does not have: the spool's set-up names
    the latter)."""
    if "shaft" in data or spool not in (data.get("spool") or {}):
        return None
    table = data.get("attach")
    return attach.on_spool(table, spool) if isinstance(table, dict) else None


def torque_variables(lay: attach.Layout | None) -> tuple[Variable, ...]:
    """The input variables of the drag and friction torques for the parts ``lay`` on the spool (module
    docstring); ``None``: the two of each kind a spool without an engine has."""
    if lay is None:
        drag = [Variable(f"{DRAG}{i + 1}", "input", 1, "N.m",
                         "drag torque of a co-simulated bearing on the spool (opposing its spin): one input "
                         "T_drag1..T_dragN per bearing of model_file on the spool, at least two")
                for i in range(MIN_PORTS)]
        rub = [Variable(f"{RUB}{i + 1}", "input", 1, "N.m",
                        "friction torque of a rub ring on the spool (opposing the spin): one input T_rub1..T_rubM "
                        "per rub ring of model_file on the spool, at least two")
               for i in range(MIN_PORTS)]
        return tuple(drag + rub)
    spare = "no further {} of the engine on this spool: set it to 0"
    drag = [Variable(f"{DRAG}{i + 1}", "input", 1, "N.m",
                     f"drag torque of bearing{lay.bearings[i]} on the spool (opposing its spin)"
                     if i < len(lay.bearings) else spare.format("bearing"))
            for i in range(max(MIN_PORTS, len(lay.bearings)))]
    rub = [Variable(f"{RUB}{i + 1}", "input", 1, "N.m",
                    f"friction torque of rubring{lay.rubrings[i]} on the spool (opposing the spin)"
                    if i < len(lay.rubrings) else spare.format("rub ring"))
           for i in range(max(MIN_PORTS, len(lay.rubrings)))]
    return tuple(drag + rub)


def kind_of(port: str) -> str | None:
    """``"drag"`` or ``"rub"`` for a torque input's name, None for another name."""
    for prefix, kind in ((DRAG, "drag"), (RUB, "rub")):
        if port.startswith(prefix) and port[len(prefix):].isdigit():
            return kind
    return None
