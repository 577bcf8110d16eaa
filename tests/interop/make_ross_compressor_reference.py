"""Writes tests/interop/data/compressor_example.toml and ross_compressor_reference.json (run with ROSS installed:
python tests/interop/make_ross_compressor_reference.py; about 6 minutes): ROSS 2.3's compressor_example (layered
shaft sections, seals and bearings with speed-dependent and cross-coupled coefficients) saved by Rotor.save, and
ROSS's own run_critical_speed of it (wn: |lambda|, wd: Im lambda, whirl, damping ratio; rtol 1e-8)."""
import json
import warnings
from pathlib import Path

import numpy as np

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import ross as rs

D = Path(__file__).with_name("data")
r = rs.compressor_example()
r.save(str(D / "compressor_example.toml"))
cs = r.run_critical_speed(num_modes=12, rtol=1e-8)
out = {"file": "compressor_example.toml", "ross_version": rs.__version__, "num_modes": 12, "rtol": 1e-8,
       "wn_rpm": [float(w) * 30 / np.pi for w in np.asarray(cs.wn())],
       "wd_rpm": [float(w) * 30 / np.pi for w in np.asarray(cs.wd())],
       "whirl": [str(w) for w in cs.whirl_direction],
       "damping_ratio": [float(z) for z in cs.damping_ratio]}
(D / "ross_compressor_reference.json").write_text(json.dumps(out, indent=1) + "\n")
print(json.dumps(out, indent=1))
