"""An FMU's saved state (FMI Get/Set/FreeFMUstate): a pointer freed with the FMU when no longer referenced."""
from __future__ import annotations

import ctypes
import weakref

from rotorcosim.fmus.fmpy_internals import c_function

#: the state functions per FMI version: get, set, free
STATE_FUNCTIONS = {"2": ("fmi2GetFMUstate", "fmi2SetFMUstate", "fmi2FreeFMUstate"),
                    "3": ("fmi3GetFMUState", "fmi3SetFMUState", "fmi3FreeFMUState")}


class FMUState:
    """An FMU state pointer, freed with the FMU when it is no longer referenced."""

    def __init__(self, comp, state):
        self.state = state
        self._finalizer = weakref.finalize(self, _free_state, comp._handle, state)


def _free_state(handle, state) -> None:
    fmu = handle.fmu
    if fmu is not None and handle.instantiated:
        try:
            c_function(fmu, STATE_FUNCTIONS[handle.version][2])(fmu.component, ctypes.byref(state))
        except Exception:
            pass
