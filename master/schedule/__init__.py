"""Schedules: which intervals a run is made of and in which phase each runs.

- :mod:`.timeline`: :class:`Interval`, :class:`Timeline` (an explicit list of intervals, e.g. 6 TM + 5 TO
  intervals), the schedule registry and :func:`from_spec` (a scenario's ``[schedule]`` table to a schedule);
- :mod:`.auto`: :class:`AutoSchedule`, thermal-only intervals once the mechanical response is steady;
- :mod:`.budget`: the time a schedule will take, estimated before a run starts.

Importing this package registers both kinds ("timeline", "auto")::

    from rotorcosim.master.schedule import Interval, Timeline
    sch = Timeline([Interval("TM", 0.1, 5e-6), Interval("TO", 10.0, 0.1)])
"""
from rotorcosim.master.schedule.timeline import (SCHEDULES, Interval, RunReport, Schedule, ScheduleError, Timeline,
                                                 UsedInterval, from_spec, register_schedule)
from rotorcosim.master.schedule.auto import AutoSchedule

__all__ = ["SCHEDULES", "AutoSchedule", "Interval", "RunReport", "Schedule", "ScheduleError", "Timeline",
           "UsedInterval", "from_spec", "register_schedule"]
