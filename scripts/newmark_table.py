#!/usr/bin/env python3
"""Newmark displacement error against Δt and accuracy preset (docs/seismic.md, issue #17).

Newmark (1965): a block on a horizontal plane with yield coefficient N = tan φ = 0.2, under a
rectangular pulse of ground acceleration A·g = 0.5 g lasting t0 = 0.5 s, slides relative to the
ground by d = V²/(2gN)(1 − N/A), V = A g t0: 0.9197 m. Writes the case and the record to a
temporary folder and prints a Markdown table. Usage: scripts/newmark_table.py [BIN]  (~10 s)"""
import json, math, os, subprocess, sys, tempfile

BIN = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "ddaslope")
A, N, T0, G = 0.5, 0.2, 0.5, 9.81
V = A * G * T0
EXACT = V * V / (2 * G * N) * (1 - N / A)

work = tempfile.mkdtemp(prefix="newmark_")
case = {"description": "Newmark (1965) rectangular pulse: block 2 x 1 m on a horizontal plane, N = tan(phi) = 0.2, "
                       "ground acceleration 0.5 g along +x for 0.5 s",
        "materials": {"rock": {"density": 2600, "young_modulus": 5e9, "poisson_ratio": 0.25}},
        "joints": {"plane": {"friction_angle": math.degrees(math.atan(N)), "cohesion": 0, "tensile_strength": 0}},
        "blocks": [{"id": "base", "material": "rock", "fixed": True, "vertices": [[-20, -2], [20, -2], [20, 0], [-20, 0]]},
                   {"id": "block", "material": "rock", "vertices": [[0, 0], [2, 0], [2, 1], [0, 1]]}],
        "monitors": [{"id": "centre", "block": "block", "point": [1, 0.5]}],
        "seismic": {"record": {"file": "pulse.csv", "units": "m/s2"}},
        "analysis": {"duration": 2.0}}
with open(os.path.join(work, "pulse.csv"), "w") as f:
    f.write(f"time,a_h\n0,{A * G}\n{T0},{A * G}\n")
path = os.path.join(work, "pulse.json")
with open(path, "w") as f:
    json.dump(case, f)


def run(args):
    out = os.path.join(work, "out")
    subprocess.run([BIN, "run", path, "--quiet", "--out", out] + args, check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    e = s["energy_J_per_m"]
    return -s["monitors"]["centre"]["ux"], s["settings"]["time_step"], e["largest_gain"] / e["scale"], s["wall_time_s"]


print(f"Closed form d = {EXACT:.4f} m.\n")
print("| setting | Δt (ms) | deformable: d (m), error | rigid: d (m), error | energy gained / scale |")
print("|---|---|---|---|---|")
rows = [("preset " + p, ["--preset", p]) for p in ("fast", "balanced", "accurate")]
rows += [("Δt", ["--time-step", str(dt)]) for dt in (0.01, 0.005, 0.002, 0.001, 0.0005)]
for label, args in rows:
    d, dt, gain, _ = run(args)
    r, _, gain_r, _ = run(args + ["--blocks", "rigid"])
    print(f"| {label} | {1e3 * dt:.3g} | {d:.4f}, {100 * (d - EXACT) / EXACT:+.2f} % | {r:.4f}, {100 * (r - EXACT) / EXACT:+.2f} % | {max(gain, gain_r):.0e} |")
