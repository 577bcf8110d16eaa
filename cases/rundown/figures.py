"""Figures of a rundown (placeholder filled below)."""


def figures(sc, data, out):
    return []
