"""The progress bar over simulated time, with a time-left estimate priced per phase (tqdm)."""
from __future__ import annotations

import math

from rotorcosim.components.contract import COUPLED, HELD
from rotorcosim.master.observer.observer import Observer, sampled_rows


class Progress(Observer):
    """A progress bar over simulated time whose time-left estimate comes from the measured wall time per step
    of each phase and the steps the schedule still has: a thermo-mechanical step costs hundreds of times a
    thermal-only one, so a rate in simulated seconds per second (tqdm's own estimate) is wrong by hours early in
    a staggered run. A phase not yet measured costs its ``prior`` price (``{COUPLED: s, HELD: s}`` per step, the
    up-front estimate's: master/schedule/budget.py), or else what the measured one does (an upper bound for
    thermal-only steps). The measurement starts once the run's first compilations are over
    (``sim.first_compiled``): on a fresh machine the first steps wait for numba, and a rate measured over them
    overstates the time left tenfold or more. Without a known plan (the automatic schedule) no
    estimate is shown."""

    stride = 64
    #: the wall time [s] a phase must have been measured over before its measured price replaces the prior
    SETTLE_S = 0.5

    def __init__(self, total: float, disable: bool = False, desc: str = "simulating", prior: dict | None = None):
        self.total = total
        self.disable = disable
        self.desc = desc
        self.prior = dict(prior or {})
        self.bar = None

    def start(self, sim, schedule):
        from tqdm import tqdm

        import time as _time

        self._clock = _time.perf_counter
        intervals = getattr(schedule, "intervals", None)
        # steps of each planned interval, in order (None: not known in advance)
        self.plan = None if intervals is None else [
            (sim.phases.role(iv.phase), max(1, int(math.ceil(iv.duration / iv.step - 1e-9)))) for iv in intervals]
        self.index = -1
        self.cost_wall = {}   # phase -> wall seconds spent in finished intervals
        self.cost_steps = {}  # phase -> steps taken in finished intervals
        self.bar = tqdm(total=self.total, unit="s", desc=self.desc, disable=self.disable, mininterval=1.0,
                        bar_format="{l_bar}{bar}| {n:.3f}/{total:.3f} s simulated [{elapsed}{postfix}]")
        self.t0 = sim.t
        self.shown = 0.0
        self._shown_at = -1e9
        # the run's first compilations (None: over, or none): until they are, nothing is measured
        first = getattr(sim, "first_compiled", None)
        self._compiling = first if first is not None and not first.is_set() else None

    def interval_start(self, sim, phase, step):
        self.stride = 1 if phase == HELD else 256
        self.index += 1
        self.phase, self.h, self.name = phase, step, sim.phase_name
        self.t_iv, self.w_iv = sim.t, self._clock()
        # where this interval's measurement starts (moved to the end of the first compilations)
        self.t_meas, self.w_meas = self.t_iv, self.w_iv

    def _settle(self, t: float) -> None:
        """The first compilations just ended: measure this interval from here."""
        if self._compiling is not None and self._compiling.is_set():
            self._compiling = None
            self.t_meas, self.w_meas = t, self._clock()

    def _cost(self, phase: str, steps_now: int, wall_now: float) -> float | None:
        w = self.cost_wall.get(phase, 0.0) + (wall_now if phase == self.phase else 0.0)
        n = self.cost_steps.get(phase, 0) + (steps_now if phase == self.phase else 0)
        if self.prior.get(phase) is not None and (w < self.SETTLE_S or not n):
            return self.prior[phase]  # too little measured yet (or nothing: still compiling)
        return w / n if n else None

    def remaining(self, t: float) -> float | None:
        """Estimated wall seconds left, from the measured cost per step of each phase (the prior until enough
        is measured)."""
        if self.plan is None or self.index >= len(self.plan):
            return None
        done = max(0, int(round((t - self.t_iv) / self.h)))
        if self._compiling is not None:
            measured, wall = 0, 0.0
        else:
            measured = max(0, int(round((t - self.t_meas) / self.h)))
            wall = self._clock() - self.w_meas
        costs = {ph: self._cost(ph, measured, wall) for ph in (COUPLED, HELD)}
        known = [c for c in costs.values() if c is not None]
        if not known:
            return None
        left = max(0, self.plan[self.index][1] - done) * (costs[self.phase] or max(known))
        for ph, n in self.plan[self.index + 1:]:
            left += n * (costs[ph] if costs[ph] is not None else max(known))
        return left

    def step(self, sim, t):
        if self.bar is None:
            return
        if self._compiling is not None:
            self._settle(t)
        done = min(self.total, t - self.t0)
        now = self._clock()
        if now - self._shown_at >= 1.0 and not self.disable:
            left = self.remaining(t)
            self.bar.set_postfix_str(f"{self.name}, ~{_hms(left)} left" if left is not None else self.name,
                                     refresh=False)
            self._shown_at = now
        self.bar.update(done - self.shown)  # tqdm redraws at most once per mininterval
        self.shown = done

    def interval_end(self, sim, used):
        if self._compiling is not None:
            self._settle(sim.t)
        if self.plan is not None and self._compiling is None:
            role = sim.phase
            self.cost_wall[role] = self.cost_wall.get(role, 0.0) + self._clock() - self.w_meas
            self.cost_steps[role] = self.cost_steps.get(role, 0) + max(
                0, int(round((sim.t - self.t_meas) / self.h)))

    def block_signals(self, sim):
        return []

    def step_block(self, sim, ks, ts, data):
        rows = sampled_rows(ks, self.stride)
        if len(rows):
            self.step(sim, float(ts[rows[-1]]))

    def end(self, sim, error):
        if self.bar is not None:
            self.step(sim, sim.t)
            self.bar.set_postfix_str("done" if error is None else "stopped", refresh=False)
            self.bar.close()

    def checkpoint_state(self):
        return None

    def restore_checkpoint(self, state):
        pass


def _hms(seconds: float) -> str:
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"
