"""The data record a component's number parameter picks (``damper = 0``: the paper's Table 3 damper #0), and
what it asks of a component that picks none (:data:`NO_RECORD`): every value the record would give, set
explicitly (a scenario sets them from its engine file)."""
from __future__ import annotations

from typing import Collection

from .contract import ContractError

#: the number of no record: the values a record gives are set explicitly
NO_RECORD = -1


def check_selection(comp, selector: str, records: Collection, needed, *, what: str, tables: str,
                    label: str = "") -> None:
    """The record number ``comp.p[selector]`` checked: one of ``records``, or :data:`NO_RECORD` with each parameter
    of ``needed`` set explicitly; else a ContractError naming the parameter. ``what`` names a record in the
    error ("Table 3 record"), ``tables`` the engine file's tables that give the values ("[damper.ID]"),
    ``label`` follows the record numbers (" (Table 3)")."""
    chosen = comp.p[selector]
    if chosen == NO_RECORD:
        missing = [name for name in needed if name not in comp.explicit]
        if missing:
            raise ContractError(f"{comp.name}: no {what} ({selector} = -1) and no {', '.join(missing)} given (a "
                                f"scenario takes them from its engine file's {tables})")
    elif chosen not in records:
        raise ContractError(f"{comp.name}.{selector} must be one of {sorted(records)}{label} or -1 (none), got "
                            f"{chosen}")
