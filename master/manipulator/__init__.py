"""Manipulators: what changes the inputs components see between intervals (libcosim's term).

- :mod:`.hold`: the staggered scheme's thermal-only hold. It decides which components freeze in a thermal-only
  interval, records the hand-off windows at the end of a thermo-mechanical interval, computes the held values
  (mean, RMS or last over the window), and fades the hand-backs in at a thermo-mechanical restart.
"""
