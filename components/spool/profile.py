"""Prescribed speed profiles of a spool, as a table of (time [s], speed [rad/s]) points, linear in between.

A constant speed is one point; a ramp from ``speed_rpm`` to ``end_speed_rpm`` starting at ``t_start`` over
``duration`` is four points (flat, ramp, flat); a table is written ``"t rpm, t rpm, ..."`` (seconds, rev/min: the
edge's units), times strictly increasing. Before the first point and after the last the speed is held.
The angle is the exact integral of the piecewise-linear speed (:func:`cumulative_angle`).

Example::

    >>> parse_table("0 9000, 1 3000")
    (array([0., 1.]), array([942.47779608, 314.15926536]))
"""
from __future__ import annotations

import math

import numpy as np

#: rev/min -> rad/s
RPM = math.pi / 30.0


def parse_table(text: str, where: str = "table") -> tuple[np.ndarray, np.ndarray]:
    """Times [s] and speeds [rad/s] of ``"t rpm, t rpm, ..."``; a ValueError naming the fault otherwise."""
    pts = [p.split() for p in text.replace(";", ",").split(",") if p.strip()]
    if not pts:
        raise ValueError(f"{where}: empty speed table (write \"t rpm, t rpm, ...\", seconds and rev/min)")
    try:
        arr = np.array([[float(a) for a in p] for p in pts])
    except ValueError:
        raise ValueError(f"{where}: {text!r} is not a list of \"t rpm\" pairs (seconds, rev/min)") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{where}: each point is two numbers \"t rpm\", got {text!r}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{where}: non-finite time or speed in {text!r}")
    if np.any(np.diff(arr[:, 0]) <= 0.0):
        raise ValueError(f"{where}: the times must increase strictly, got {arr[:, 0].tolist()} s")
    if np.any(arr[:, 1] < 0.0):
        raise ValueError(f"{where}: speeds must be >= 0 rev/min (a spool turns one way), got {arr[:, 1].tolist()}")
    return arr[:, 0].copy(), arr[:, 1] * RPM


def ramp_table(speed_rpm: float, end_speed_rpm: float, t_start: float, duration: float):
    """The table of a linear ramp (constant before ``t_start`` and after ``t_start + duration``)."""
    if not duration > 0.0:
        raise ValueError(f"ramp duration must be > 0 s, got {duration}")
    t = np.array([t_start, t_start + duration])
    return t, np.array([speed_rpm, end_speed_rpm]) * RPM


def cumulative_angle(t: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The angle at each table point, from 0 at the first (trapezoids: exact for a piecewise-linear speed)."""
    out = np.zeros(t.size)
    if t.size > 1:
        out[1:] = np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))
    return out
