"""Cases: what a particular study adds on top of the generic master (its results, figures, commands).

A case is a package that plugs into the master the way a user's own case would (see
:mod:`rotorcosim.master.case`). The one shipped is :mod:`.blade_loss`, the reference paper's blade-loss study.
"""
