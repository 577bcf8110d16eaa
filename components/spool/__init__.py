"""A spool's speed as a state: prescribed (constant, ramp, table of time -> rev/min) or driven by its torque
balance ``J dOmega/dt = T_drive - T_drag - T_rub - T_aero(Omega)`` (component.Spool)."""
