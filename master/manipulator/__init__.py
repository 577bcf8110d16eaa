"""Manipulators: what changes the inputs components see between intervals (libcosim's term).

- :mod:`.hold`: the staggered scheme's thermal-only hold. It decides which components freeze in a thermal-only
  interval and sets the links up for each interval;
- :mod:`.handoff`: its hand-offs: the windows recorded at the end of a thermo-mechanical interval and the values
  held over a thermal-only one (mean, RMS or last over the window, or the law that follows the producer's TO
  output);
- :mod:`.error_estimate`: what the hold measures of its own error (:class:`~.error_estimate.HoldReport`, the
  replay);
- :mod:`.restart`: the hand-backs faded in at a thermo-mechanical restart.
"""
