"""The phases a scenario declares: its names for the two roles a phase can play.

A staggered run alternates intervals of two kinds. In the *coupled* phase every component steps and every link
carries its producer's outputs; in the *held* phase only the components that declare it step and the master holds
the outputs of the others (master/manipulator/hold.py). Components name the phases they take part in by these
roles (``components.contract.COUPLED`` / ``HELD``); a scenario names its phases as its field does, in its
``[schedule.phases]`` table::

    [schedule.phases]
    coupled = "TM"     # thermo-mechanical (the default names: those of the component contract)
    held = "TO"        # thermal-only

and its timeline's intervals, the run's summary (``timeline[].phase``), the time series' phase codes
(0 = coupled, 1 = held) and ``Result.phase`` use those names.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

from rotorcosim.components.contract import COUPLED, HELD, PHASES, ContractError

#: the keys of ``[schedule.phases]``: the roles, in the order of their codes in the time series
ROLES = ("coupled", "held")


@dataclass(frozen=True)
class Phases:
    """A scenario's names of the coupled and the held phase.

    >>> p = Phases(coupled="mechanical", held="thermal")
    >>> p.role("thermal") == HELD, p.name(COUPLED), p.names
    (True, 'mechanical', ('mechanical', 'thermal'))
    """

    coupled: str = COUPLED
    held: str = HELD

    def __post_init__(self):
        for key in ROLES:
            v = getattr(self, key)
            if not isinstance(v, str) or not v.strip():
                raise ContractError(f"phases: {key} must be a non-empty name, got {v!r}")
        if self.coupled == self.held:
            raise ContractError(f"phases: coupled and held must differ, both are {self.coupled!r}")

    @classmethod
    def from_spec(cls, spec: Mapping | None) -> "Phases":
        """The phases of a ``[schedule.phases]`` table (None or missing keys: the default names)."""
        spec = dict(spec or {})
        unknown = set(spec) - set(ROLES)
        if unknown:
            raise ContractError(f"phases: unknown key(s) {sorted(unknown)}; known: {list(ROLES)}")
        return cls(**spec)

    @property
    def names(self) -> tuple[str, str]:
        """The names, in the order of their codes (0 coupled, 1 held)."""
        return (self.coupled, self.held)

    def role(self, name: str) -> str:
        """The role (``COUPLED`` or ``HELD``) of the phase called ``name``; a ContractError for a name the
        scenario does not declare."""
        if name == self.coupled:
            return COUPLED
        if name == self.held:
            return HELD
        raise ContractError(f"phase {name!r} is not one the scenario declares ({self.coupled!r} coupled, "
                            f"{self.held!r} held: [schedule.phases])")

    def name(self, role: str) -> str:
        """The scenario's name of ``role``."""
        return self.coupled if role == COUPLED else self.held

    def description(self, tags: bool = True) -> str:
        """What the time series' phase codes mean, as its attributes say it (the default names keep the words
        of the files written before phases were declared); ``tags``: with the names in brackets."""
        if self.names == PHASES:
            return ("0 = thermo-mechanical (TM), 1 = thermal-only (TO)" if tags
                    else "0 = thermo-mechanical, 1 = thermal-only")
        return f"0 = {self.coupled} (coupled), 1 = {self.held} (held)"

    @staticmethod
    def code(role: str) -> int:
        """The role's code in the time series: 1 held, else 0 (coupled, and the first sample, taken before any
        interval has started)."""
        return 1 if role == HELD else 0
