"""Writes tests/interop/data (run with ROSS installed: python tests/interop/make_ross_reference.py): ROSS 2.3's own
example rotors saved by Rotor.save, and ROSS's results for them (critical speeds, unbalance responses)."""
import json
import numpy as np
import ross as rs
out = {}
D = str(__import__("pathlib").Path(__file__).with_name("data"))
for name, mk, fname in (("rotor_example", rs.rotor_example, "rotor_example.toml"),
                         ("coaxrotor_example", rs.coaxrotor_example, "coaxrotor_example.toml")):
    r = mk()
    r.save(f"{D}/{fname}")
    cs = r.run_critical_speed(num_modes=24, rtol=1e-10)
    wn = np.asarray(cs.wn())
    fw = sorted(float(w * 30 / np.pi) for w, d in zip(wn, cs.whirl_direction) if d == "Forward")
    nd = int(r.disk_elements[0].n)
    resp = []
    for rpm in (0.7 * fw[0], 1.6 * fw[0]):
        W = rpm * np.pi / 30
        fr = r.run_unbalance_response(nd, 1e-3, 0.0, frequency=np.array([W]))
        R = np.asarray(fr.forced_resp)[:, 0]
        resp.append({"rpm": rpm, "node": nd, "me_kgm": 1e-3, "abs_x": float(abs(R[nd * r.number_dof])),
                     "abs_y": float(abs(R[nd * r.number_dof + 1]))})
    out[name] = {"file": fname, "ross_version": rs.__version__, "forward_synchronous_rpm": fw[:4], "response": resp}
json.dump(out, open(f"{D}/ross_reference.json", "w"), indent=1)
print(json.dumps(out, indent=1))
