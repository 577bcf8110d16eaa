"""The rotor component: the flexible dual-rotor engine + casing, MTA-reduced, Newmark-beta.

Modules: ``beam`` (Timoshenko shaft element, disk), ``hexa`` (8-node solid), ``model`` (the full FE model from
``data/engine.toml``), ``mta`` (eqs. 16-22), ``newmark`` (the integrator), ``kernel`` (the compiled step),
``component`` (:class:`Rotor`, registered as ``rotor.mta``), ``critical`` (synchronous critical speeds, Campbell),
``calibration`` (the two-knob fit to 8500 / 10 200 rev/min), ``verification`` (full vs reduced transient),
``engine_check`` (every problem of an engine file by name, its masses and inertias), ``response`` (the
synchronous unbalance response). The engine format: docs/reference/engine-format.md.
"""
