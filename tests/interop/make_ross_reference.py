"""Writes tests/interop/data (run with ROSS installed: python tests/interop/make_ross_reference.py): ROSS 2.3's own
example rotors saved by Rotor.save, and ROSS's results for them (critical speeds, unbalance responses below, at and
above the first forward critical speed, the damped modes at it). With names (python make_ross_reference.py NAME...)
only those examples are written, the others' entries kept: ROSS's whirl labels of nearly circular orbits change
from run to run, so a run moves the other entries' forward critical speeds."""
import json
import sys
from pathlib import Path

import numpy as np
import ross as rs

D = str(Path(__file__).with_name("data"))
only = set(sys.argv[1:])
out = json.loads(Path(D, "ross_reference.json").read_text()) if only else {}
for name, mk, fname in (("rotor_example", rs.rotor_example, "rotor_example.toml"),
                         ("coaxrotor_example", rs.coaxrotor_example, "coaxrotor_example.toml"),
                         ("rotor_example_with_damping", rs.rotor_example_with_damping,
                          "rotor_example_with_damping.toml"),
                         ("rotor_example_6dof", rs.rotor_example_6dof, "rotor_example_6dof.toml")):
    if only and name not in only:
        continue
    r = mk()
    r.save(f"{D}/{fname}")
    try:
        cs = r.run_critical_speed(num_modes=24, rtol=1e-10)
    except RuntimeError:       # rotor_example_with_damping: a high mode's fixed point does not converge
        cs = r.run_critical_speed(num_modes=8, rtol=1e-10)
    wn = np.asarray(cs.wn())
    fw = sorted(float(w * 30 / np.pi) for w, d in zip(wn, cs.whirl_direction) if d == "Forward")
    # rotor_example_with_damping's modes are all "Mixed" (bearings of kxx 9.5e5, kyy 1.09e8 N/m): its first
    # critical speed of any whirl
    first = fw[0] if fw else float(min(np.asarray(cs.wn())) * 30 / np.pi)
    modal = r.run_modal(first * np.pi / 30, num_modes=16)
    modes = [{"wn_rad_s": float(w), "log_dec": float(d), "whirl": str(h)}
             for w, d, h in zip(modal.wn, modal.log_dec, modal.whirl_direction())][:8]
    nd = int(r.disk_elements[0].n)
    resp = []
    # at the critical speed only where the rotor is damped (an undamped one's response there has no finite value)
    damped = any(abs(m["log_dec"]) > 1e-6 for m in modes)
    for rpm in (0.7 * first, first, 1.6 * first) if damped else (0.7 * first, 1.6 * first):
        W = rpm * np.pi / 30
        fr = r.run_unbalance_response(nd, 1e-3, 0.0, frequency=np.array([W]))
        R = np.asarray(fr.forced_resp)[:, 0]
        resp.append({"rpm": rpm, "node": nd, "me_kgm": 1e-3, "abs_x": float(abs(R[nd * r.number_dof])),
                     "abs_y": float(abs(R[nd * r.number_dof + 1]))})
    out[name] = {"file": fname, "ross_version": rs.__version__, "forward_synchronous_rpm": fw[:4], "response": resp,
                 "first_critical_rpm": first, "modes_at_first_critical": modes}
json.dump(out, open(f"{D}/ross_reference.json", "w"), indent=1)
print(json.dumps(out, indent=1))
