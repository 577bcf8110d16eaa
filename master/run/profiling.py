"""Where the time goes: wall time spent in each component's do_step and in the master around them."""
from __future__ import annotations

import time
from typing import Sequence


class StepTimer:
    """Wraps the ``do_step`` of each component of a system (instance attribute), summing its wall time."""

    def __init__(self, system, names: Sequence[str] | None = None):
        self.seconds: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        for name in names or list(system.components):
            comp = system.components[name]
            self.seconds[name] = 0.0
            self.calls[name] = 0
            comp.do_step = self._wrap(name, comp.do_step)

    def _wrap(self, name, step):
        clock = time.perf_counter
        seconds, calls = self.seconds, self.calls

        def timed(t, h):
            t0 = clock()
            step(t, h)
            seconds[name] += clock() - t0
            calls[name] += 1

        return timed

    def table(self, total_wall: float) -> str:
        """A text table: per component its calls, total and per-call time and share of ``total_wall`` [s] (the
        run's wall time); the master's share is what is left."""
        lines = [f"{'component':<12} {'calls':>9} {'total s':>9} {'us/call':>9} {'share':>7}"]
        inside = 0.0
        for name, s in sorted(self.seconds.items(), key=lambda kv: -kv[1]):
            n = self.calls[name]
            inside += s
            lines.append(f"{name:<12} {n:>9d} {s:>9.3f} {1e6 * s / max(n, 1):>9.2f} {100 * s / total_wall:>6.1f}%")
        lines.append(f"{'master':<12} {'':>9} {total_wall - inside:>9.3f} {'':>9} {100 * (total_wall - inside) / total_wall:>6.1f}%")
        return "\n".join(lines)
