#!/usr/bin/env python3
"""Newmark displacement error against Δt and accuracy preset (docs/seismic.md, issue #17).

1. Newmark (1965): a block on a horizontal plane with yield coefficient N = tan φ = 0.2, under a
   rectangular pulse of ground acceleration A·g = 0.5 g lasting t0 = 0.5 s, slides relative to the
   ground by d = V²/(2gN)(1 − N/A), V = A g t0: 0.9197 m.
2. A block on α = 20°, φ = 30° (k_y = tan 10° = 0.176) under three cycles of a 2 Hz sine of 0.4 g
   along +x: its downslope slide against an accurate integration (1e-5 s steps) of the sliding-block
   equation s'' = g sin α + a cos α − tan φ (g cos α − a sin α), downslope only.
Writes the cases and records to a temporary folder and prints Markdown tables.
Usage: scripts/newmark_table.py [BIN]  (~20 s)"""
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


def run(case_path, args, along):
    """Runs a case; returns the centre's final displacement along the unit vector `along`, Δt and
    the energy gained over the energy scale."""
    out = os.path.join(work, "out")
    subprocess.run([BIN, "run", case_path, "--quiet", "--out", out] + args, check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    e = s["energy_J_per_m"]
    m = s["monitors"]["centre"]
    return m["ux"] * along[0] + m["uy"] * along[1], s["settings"]["time_step"], e["largest_gain"] / e["scale"]


def table(case_path, exact, along):
    print("| setting | Δt (ms) | deformable: d (m), error | rigid: d (m), error | energy gained / scale |")
    print("|---|---|---|---|---|")
    rows = [("preset " + p, ["--preset", p]) for p in ("fast", "balanced", "accurate")]
    rows += [("Δt", ["--time-step", str(dt)]) for dt in (0.01, 0.005, 0.002, 0.001, 0.0005)]
    for label, args in rows:
        d, dt, gain = run(case_path, args, along)
        r, _, gain_r = run(case_path, args + ["--blocks", "rigid"], along)
        print(f"| {label} | {1e3 * dt:.3g} | {d:.4f}, {100 * (d - exact) / exact:+.2f} % | "
              f"{r:.4f}, {100 * (r - exact) / exact:+.2f} % | {max(gain, gain_r):.0e} |")


print(f"Rectangular pulse: closed form d = {EXACT:.4f} m.\n")
table(path, EXACT, (-1.0, 0.0))

# 2. The sine on an incline rising toward +x (the valley along −x).
ALPHA, PHI, AMP, FREQ, CYCLES, DURATION = math.radians(20), math.radians(30), 0.4 * G, 2.0, 3, 2.5
u = (math.cos(ALPHA), math.sin(ALPHA))
n = (-math.sin(ALPHA), math.cos(ALPHA))
times = [1e-3 * k for k in range(int(CYCLES / FREQ * 1000) + 1)]
accel = [AMP * math.sin(2 * math.pi * FREQ * t) for t in times]


def ground(t):
    if t < times[0] or t > times[-1]:
        return 0.0
    k = min(int(t / 1e-3), len(times) - 2)
    w = (t - times[k]) / 1e-3
    return (1 - w) * accel[k] + w * accel[k + 1]


def sliding(h=1e-5):
    s = v = 0.0
    t = 0.0
    while t < DURATION:
        a = ground(t + h / 2)
        drive = G * math.sin(ALPHA) + a * math.cos(ALPHA) - math.tan(PHI) * (G * math.cos(ALPHA) - a * math.sin(ALPHA))
        if v <= 0 and drive <= 0:
            v = 0.0
        elif v + h * drive < 0:
            s += v * v / (2 * -drive)
            v = 0.0
        else:
            s += h * (2 * v + h * drive) / 2
            v += h * drive
        t += h
    return s


def p(along, up):
    return [along * u[0] + up * n[0], along * u[1] + up * n[1]]


incline = {"description": "Block 2 x 1 m on a 20 degree plane, phi = 30 degrees, under three cycles of a 2 Hz sine of 0.4 g along +x",
           "materials": case["materials"],
           "joints": {"plane": {"friction_angle": 30, "cohesion": 0, "tensile_strength": 0}},
           "blocks": [{"id": "ramp", "material": "rock", "fixed": True, "vertices": [p(-2, -3), p(30, -3), p(30, 0), p(-2, 0)]},
                      {"id": "block", "material": "rock", "vertices": [p(10, 0), p(12, 0), p(12, 1), p(10, 1)]}],
           "monitors": [{"id": "centre", "block": "block", "point": p(11, 0.5)}],
           "seismic": {"record": {"file": "sine.csv", "units": "m/s2"}},
           "analysis": {"duration": DURATION}}
with open(os.path.join(work, "sine.csv"), "w") as f:
    f.write("time,a_h\n" + "".join(f"{t!r},{a!r}\n" for t, a in zip(times, accel)))
sine_path = os.path.join(work, "sine.json")
with open(sine_path, "w") as f:
    json.dump(incline, f)
exact = sliding()
print(f"\nSine on an incline: sliding-block equation d = {exact:.4f} m.\n")
table(sine_path, exact, (-u[0], -u[1]))
