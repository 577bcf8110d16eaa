"""The engine-to-airframe interface of an installed engine (an engine on mounts and an airframe): its loads and
vibration as results (``results.py``: summary.json ``interface``) and figures (``figures.py``), for any case whose
scenario has an airframe component."""
