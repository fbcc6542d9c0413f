#!/usr/bin/env python3
"""Writes the block-on-incline benchmark cases of ../shared/reference/benchmarks.md (A1-A4, A6)
into cases/. The inclined geometry is computed here so the JSON carries exact coordinates.
Run: python3 scripts/make_benchmark_cases.py"""
import json, math, os

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, "..", "cases")


def r(v):
    return round(v, 12)


def incline_case(alpha_deg, b, h, s0, length, rho, g, phi_deg, c=0.0, young=5e9):
    """Fixed ramp whose top is the slope line through the origin, and a b x h block resting on it
    with its lower (downslope) corner at distance s0 along the slope."""
    a = math.radians(alpha_deg)
    u = (math.cos(a), math.sin(a))     # up the slope
    n = (-math.sin(a), math.cos(a))    # out of the slope
    base = [[0.0, -2.0], [r(length * u[0]), -2.0], [r(length * u[0]), r(length * u[1])], [0.0, 0.0]]
    p = lambda s, t: [r(s * u[0] + t * n[0]), r(s * u[1] + t * n[1])]
    block = [p(s0, 0), p(s0 + b, 0), p(s0 + b, h), p(s0, h)]
    centre = p(s0 + b / 2, h / 2)
    return {
        "gravity": [0, -g],
        "materials": {"rock": {"density": rho, "young_modulus": young, "poisson_ratio": 0.25}},
        "joints": {"interface": {"friction_angle": phi_deg, "cohesion": c, "tensile_strength": 0}},
        "default_joint": "interface",
        "blocks": [
            {"id": "ramp", "material": "rock", "fixed": True, "vertices": base},
            {"id": "block", "material": "rock", "vertices": block},
        ],
        "monitors": [{"id": "centre", "block": "block", "point": centre}],
    }, p


def write(name, case):
    with open(os.path.join(CASES, name), "w") as f:
        json.dump(case, f, indent=2)
        f.write("\n")


def sliding(name, alpha, b, h, rho, g, phi, source):
    case, _ = incline_case(alpha, b, h, s0=15.0, length=30.0, rho=rho, g=g, phi_deg=phi)
    a = g * (math.sin(math.radians(alpha)) - math.cos(math.radians(alpha)) * math.tan(math.radians(phi)))
    case = {"description": f"{source}: block {b} x {h} m sliding on a {alpha} degree plane, phi = {phi} degrees, "
                           f"c = 0. Closed form a = g (sin a - cos a tan phi) = {a:.6f} m/s^2, d = a t^2 / 2.",
            **case,
            "analysis": {"duration": 2.0, "time_step": 0.001},
            "expected": [
                {"monitor": "centre", "quantity": "displacement", "time": 1.0, "value": r(a / 2),
                 "relative_tolerance": 0.005, "source": f"{source}: d(1 s) = a/2"},
                {"monitor": "centre", "quantity": "displacement", "time": 2.0, "value": r(2 * a),
                 "relative_tolerance": 0.005, "source": f"{source}: d(2 s) = 2a"},
                {"monitor": "centre", "quantity": "speed", "time": 1.0, "value": r(a),
                 "relative_tolerance": 0.005, "source": f"{source}: v(1 s) = a"},
            ]}
    write(name, case)


def main():
    # A1: free fall above a fixed ground that sets the model size (w0).
    write("free_fall.json", {
        "description": "A1 free fall: a 1 x 1 m block released 10 m above the ground, g = 9.81. "
                       "y(t) = g t^2/2; Newmark beta = 1/2, gamma = 1 integrates constant acceleration exactly.",
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": 2600, "young_modulus": 5e9, "poisson_ratio": 0.25}},
        "joints": {"bedding": {"friction_angle": 30, "cohesion": 0, "tensile_strength": 0}},
        "default_joint": "bedding",
        "blocks": [
            {"id": "ground", "material": "rock", "fixed": True, "vertices": [[-10, -2], [10, -2], [10, 0], [-10, 0]]},
            {"id": "falling", "material": "rock", "vertices": [[-0.5, 10], [0.5, 10], [0.5, 11], [-0.5, 11]]},
        ],
        "monitors": [{"id": "m1", "block": "falling", "point": [0, 10.5]}],
        "analysis": {"duration": 1.0, "time_step": 0.001},
        "expected": [
            {"monitor": "m1", "quantity": "uy", "time": 1.0, "value": -4.905, "relative_tolerance": 1e-9,
             "source": "A1: y(1 s) = g/2"},
            {"monitor": "m1", "quantity": "vy", "time": 1.0, "value": -9.81, "relative_tolerance": 1e-9,
             "source": "A1: v(1 s) = g"},
        ]})
    sliding("sliding_block_40deg.json", 40, 10, 5, 2000, 10, 20, "A2 (Itasca 3DEC sliding-block geometry)")
    sliding("sliding_block_30deg.json", 30, 2, 1, 2600, 9.81, 20, "A4")

    case, _ = incline_case(40, 10, 10, s0=10.0, length=30.0, rho=2000, g=10, phi_deg=40.1)
    write("stable_block_40deg.json", {
        "description": "A3 (3DEC stable case): block 10 x 10 m on a 40 degree plane with phi = 40.1 degrees. "
                       "No sliding: only the elastic settling of the contact springs, below 1e-3 b = 0.01 m.",
        **case,
        "analysis": {"duration": 2.0, "time_step": 0.001},
        "expected": [{"monitor": "centre", "quantity": "displacement", "at_most": 0.01,
                      "source": "A3: displacement < 1e-3 b"}]})

    # B2: cohesive block, stiff (rigid compared with its springs: the founding paper's setting).
    case, _ = incline_case(40, 10, 5, s0=15.0, length=30.0, rho=2000, g=10, phi_deg=20, c=42000, young=5e11)
    case["joints"]["interface"]["weakening_distance"] = 0  # original DDA's brittle bond, as in the paper
    write("cohesive_block_42kpa.json", {
        "description": "B2 (founding paper's case): the A2 block (b = 10, h = 5 m, alpha = 40, phi = 20 degrees) "
                       "with cohesion c = 42 kPa, factor of safety (c b + N tan phi)/T = 1.087. The edge-to-edge "
                       "treatment (default) holds it. Run with --contact-treatment vertex to see original DDA "
                       "slide it: its upslope half fails first (threshold about 48 kPa for a block rigid compared "
                       "with its springs, as here: E = 500 GPa, penalty 200 GN/m). The bond is brittle "
                       "(weakening_distance 0: lost the moment a contact slides), as in the paper; with the "
                       "default softening joint both treatments hold it (docs/contact-model.md).",
        **case,
        "analysis": {"duration": 1.0, "time_step": 0.001, "penalty": 2e11},
        "expected": [{"monitor": "centre", "quantity": "displacement", "at_most": 0.01,
                      "source": "B2: c = 42 kPa > c_cr = 36.40 kPa, holds with the edge-to-edge treatment"}]})

    # C: Hoek & Bray planar failure, dry (benchmarks.md C).
    h, xc, gap, psi, face = 20.0, 20.0, 0.05, 35.0, 60.0
    t, cot = math.tan(math.radians(psi)), 1 / math.tan(math.radians(face))
    wedge = [[0.0, 0.0], [xc, r(xc * t)], [xc, h], [r(h * cot), h]]
    area = 0.5 * abs(sum(wedge[i][0] * wedge[(i + 1) % 4][1] - wedge[(i + 1) % 4][0] * wedge[i][1] for i in range(4)))
    cx = sum((wedge[i][0] + wedge[(i + 1) % 4][0]) * (wedge[i][0] * wedge[(i + 1) % 4][1] - wedge[(i + 1) % 4][0] * wedge[i][1]) for i in range(4)) / (6 * area)
    cy = sum((wedge[i][1] + wedge[(i + 1) % 4][1]) * (wedge[i][0] * wedge[(i + 1) % 4][1] - wedge[(i + 1) % 4][0] * wedge[i][1]) for i in range(4)) / (6 * area)
    w, length, c, phi = 2600 * 9.81 * area, xc / math.cos(math.radians(psi)), 25e3, 30.0
    fs = (c * length + w * math.cos(math.radians(psi)) * math.tan(math.radians(phi))) / (w * math.sin(math.radians(psi)))
    write("planar_failure.json", {
        "description": f"C (Hoek & Bray planar failure, dry): a slope with a {face:.0f} degree face and a horizontal crest "
                       f"{h:.0f} m above the point where a {psi:.0f} degree sliding plane daylights; a vertical tension "
                       f"crack {xc:.0f} m behind, left open by {gap} m so it carries nothing. c = {c/1e3:.0f} kPa, "
                       f"phi = {phi:.0f} degrees. Hoek & Bray: FS = (c A + W cos psi tan phi)/(W sin psi) = {fs:.4f} "
                       f"(W = {w/1e3:.1f} kN/m, A = {length:.3f} m). Try: ddaslope fos cases/planar_failure.json",
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": 2600, "young_modulus": 10e9, "poisson_ratio": 0.25}},
        "joints": {"sliding_plane": {"friction_angle": phi, "cohesion": c, "tensile_strength": 0}},
        "default_joint": "sliding_plane",
        "blocks": [
            {"id": "rock_mass", "material": "rock", "fixed": True,
             "vertices": [[-10, -10], [xc + 20, -10], [xc + 20, h], [xc + gap, h], [xc + gap, r((xc + gap) * t)],
                          [0, 0], [r(-5 * cot), -5], [-10, -5]]},
            {"id": "wedge", "material": "rock", "vertices": wedge},
        ],
        "monitors": [{"id": "wedge", "block": "wedge", "point": [r(cx), r(cy)]}],
        "analysis": {"duration": 1.0, "time_step": 0.001},
        "expected": [{"monitor": "wedge", "quantity": "displacement", "at_most": 0.01,
                      "source": f"C: FS = {fs:.4f} > 1, the wedge holds"}]})

    # C with water: the same slope with its tension crack full of water, draining to the toe.
    zw = h - xc * t
    u, v = 9810 * zw * length / 2, 9810 * zw * zw / 2
    fs_w = (c * length + (w * math.cos(math.radians(psi)) - u - v * math.sin(math.radians(psi))) * math.tan(math.radians(phi))) / \
           (w * math.sin(math.radians(psi)) + v * math.cos(math.radians(psi)))
    wet = json.load(open(os.path.join(CASES, "planar_failure.json")))
    wet["description"] = (f"C with water (Hoek & Bray): the planar failure of planar_failure.json with its tension crack "
                          f"full of water (zw = {zw:.3f} m), draining to the toe along the sliding plane: a phreatic line "
                          f"from the toe to the crack's water surface. U = gw zw A/2 = {u/1e3:.1f} kN/m on the plane, "
                          f"V = gw zw^2/2 = {v/1e3:.1f} kN/m in the crack; FS = (c A + (W cos psi - U - V sin psi) tan phi)"
                          f"/(W sin psi + V cos psi) = {fs_w:.4f}: the wedge slides. Try: ddaslope fos cases/planar_failure_water.json")
    wet["water"] = {"phreatic_line": [[0, 0], [xc, r(xc * t + zw)]], "unit_weight": 9810}
    wet["expected"] = [{"monitor": "wedge", "quantity": "displacement", "at_least": 0.1,
                        "source": f"C with water: FS = {fs_w:.4f} < 1, the wedge slides"}]
    write("planar_failure_water.json", wet)

    # A6: toppling. Rigid rotation about the downslope corner: torque W (b cos a - h sin a)/2,
    # I = m (b^2 + h^2)/3, so the initial angular acceleration is known in closed form.
    alpha, b, h, g = 30.0, 10.0, 25.0, 9.81
    case, p = incline_case(alpha, b, h, s0=5.0, length=40.0, rho=2600, g=g, phi_deg=40)
    a = math.radians(alpha)
    ang_acc = 1.5 * g * (h * math.sin(a) - b * math.cos(a)) / (b * b + h * h)
    t = 0.5
    top = math.hypot(b, h) * 0.5 * ang_acc * t * t  # small-angle: corner moves r * theta
    case["monitors"] = [{"id": "top", "block": "block", "point": p(5.0 + b, h)},
                        {"id": "toe", "block": "block", "point": p(5.0, 0)}]
    write("toppling_block.json", {
        "description": "A6 toppling: block b = 10, h = 25 m on a 30 degree plane, phi = 40 degrees. "
                       "b/h = 0.4 < tan 30 = 0.577: it topples about its downslope corner without sliding. "
                       f"Initial angular acceleration 1.5 g (h sin a - b cos a)/(b^2 + h^2) = {ang_acc:.6f} rad/s^2.",
        **case,
        "analysis": {"duration": 1.0, "time_step": 0.001},
        "expected": [
            {"monitor": "top", "quantity": "displacement", "time": t, "value": r(top), "relative_tolerance": 0.03,
             "source": "A6: rigid rotation about the toe, corner displacement r theta with theta = alpha t^2/2"},
            {"monitor": "toe", "quantity": "displacement", "at_most": 0.01,
             "source": "A6: the pivot does not slide (phi = 40 > alpha = 30)"},
        ]})

    toppling_slope()


def toppling_slope():
    """D: the Alejano & Alonso block-toppling slope (benchmarks.md D), in two toe conditions."""
    rho = 25e3 / 9.81  # 25 kN/m3
    crest_x = 20 - 9.85 / math.tan(math.radians(30))  # basal joint at 30 deg from the toe to the top
    source = ("Benchmark D (../shared/reference/benchmarks.md): the Alejano & Alonso block-toppling slope as "
              "transcribed from the Rocscience RS2 joint verification manual. 9.85 m face at 58.65 deg from the toe "
              "(20, 10) to the crest (14, 19.85); basal joint at 30 deg from the toe to "
              f"({crest_x:.4f}, 19.85); columns between joints at 64 deg dipping into the slope, 1.6 m apart (the "
              "transcription's 22 joints span the whole 30 x 19.85 m section; 12 cross the slide mass; the set is "
              "placed through the toe); all joints phi = 31 deg, c = 0; rock 25 kN/m3, E = 20 GPa, nu = 0.3. "
              "Published factors of safety: Goodman-Bray limit equilibrium 0.76, UDEC 0.87, RS2 0.86/0.82. "
              "The rock below the basal joint is one fixed block here (the published models joint it too). ")
    common = {
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": r(rho), "young_modulus": 2e10, "poisson_ratio": 0.3}},
        "joints": {"joint": {"friction_angle": 31, "cohesion": 0, "tensile_strength": 0}},
        "default_joint": "joint",
    }
    section = {"sliding_surface": [[r(crest_x), 19.85], [20, 10]], "base_depth": 10, "material": "rock",
               "sliding_joint": "joint", "joint_sets": [{"angle": 64, "spacing": 1.6, "origin": [20, 10]}]}
    monitors = [{"id": "crest", "point": [13.8, 19.6]}, {"id": "toe", "point": [19.6, 10.4]}]
    analysis = {"duration": 1.0, "time_step": 0.001, "failure_displacement": 0.05}
    write("toppling_slope.json", {
        "description": source + "Here the basal joint daylights 1 m above the bench (a step at the toe), so the toe "
                       "column can slide out along it as Goodman & Bray assume. DDA factor of safety 0.895 "
                       "(docs/calibration.md, benchmark D): at phi = 31 deg the slope topples. "
                       "Try: ddaslope fos cases/toppling_slope.json",
        **common,
        "section": {"ground": [[0, 19.85], [14, 19.85], [20, 10], [20, 9], [30, 9]], **section},
        "monitors": monitors, "analysis": analysis,
        "expected": [{"monitor": "crest", "quantity": "displacement", "at_least": 0.05,
                      "source": "D: published factors of safety 0.76-0.87 < 1, the slope fails at phi = 31 deg"}]})
    write("toppling_slope_bench_toe.json", {
        "description": source + "Here the basal joint ends exactly at the bench level, as transcribed: the bench "
                       "blocks the toe column's path along the basal joint, the columns cannot slide out and the "
                       "slope holds until phi falls below the 30 deg base (DDA factor of safety 1.048, "
                       "docs/calibration.md, benchmark D). Compare cases/toppling_slope.json",
        **common,
        "section": {"ground": [[0, 19.85], [14, 19.85], [20, 10], [30, 10]], **section},
        "monitors": monitors, "analysis": analysis,
        "expected": [{"monitor": "crest", "quantity": "displacement", "at_most": 0.005,
                      "source": "D with the toe obstructed: phi = 31 deg exceeds the 30 deg basal joint, and the toe "
                                "column cannot leave along it, so the slope holds (docs/calibration.md)"}]})


if __name__ == "__main__":
    main()
