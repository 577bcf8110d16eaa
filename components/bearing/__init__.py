"""Ball bearings #0 and #5 of the power turbine (paper section 2.2, eqs. 1-10, Table 3).

component.py  the ``bearing.hertz`` component (BallBearing): balls, cage, outer race + journal in time
kernel.py     its numba time-stepping kernel (contact forces, sub-steps, linearly implicit journal)
static.py     quasi-static equilibrium (preloaded rest state, ``rotorcosim bearing-static``)
hertz.py      Hertz point-contact constants (eqs. 9-10)
geometry.py   Table 3 data and derived geometry (data/bearings.toml)
drag.py       Palmgren drag torque; oil.py the SAE 30 viscosity
cli.py        ``rotorcosim bearing-static``
"""
