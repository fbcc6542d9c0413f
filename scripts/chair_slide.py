#!/usr/bin/env python3
"""Chair-shaped reservoir bedding slide: a synthetic test case and its limit equilibrium with cohesion.

What: `case` writes cases/chair_slide.json, a section of a slide mass ~50 m thick on a bedding
sliding surface that dips 30 deg in its upper part and flattens onto an 8 deg lower part (the "chair"),
cut by vertical joints every 50 m (one through the kink), its toe submerged by a reservoir.
`le` gives the critical cohesion (or friction) of the sliding surface by the multi-wedge limit
equilibrium of those vertical slices (scripts/vajont_limit_equilibrium.py, extended to cohesion),
for interface friction delta = 0 (Janbu-simplified-like: the weakest, so the highest critical
cohesion) and delta = the internal joints' friction (the strongest, the lowest critical cohesion),
and each slice's critical cohesion standing alone. The rigorous reference on the same slices
(Spencer and Morgenstern-Price, force and moment equilibrium): scripts/spencer.py.

Why: the case is built so that a block of the 30 deg segment alone needs far more cohesion (>= 2x)
than the whole slide, whose flat, submerged toe acts as a buttress for the upper blocks. DDA's
critical cohesion (`ddaslope critical cases/chair_slide.json --joint sliding_surface --solve cohesion
--friction 18`) can then be compared with the limit-equilibrium range: in DDA the cohesion of a
contact is lost once it slides, so whether the buttress effect survives is the question.

Run: python3 scripts/chair_slide.py case [--out cases/chair_slide.json]
     python3 scripts/chair_slide.py le --friction 18 [--delta D] [--case cases/chair_slide.json]
     python3 scripts/chair_slide.py le --cohesion 60e3 [--delta D]
"""
import argparse, json, math, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
from vajont_limit_equilibrium import section_slices, toe_thrust, critical_friction, value_at  # noqa: E402
import spencer  # noqa: E402

ROOT = os.path.dirname(HERE)
CASE_PATH = os.path.join(ROOT, "cases", "chair_slide.json")

# Geometry (synthetic, m): crown at x = 0, kink at X_KINK, toe at X_TOE on the valley floor y = 0.
X_KINK, X_TOE = 500.0, 850.0
UPPER_DIP, LOWER_DIP = 30.0, 8.0      # deg, sliding surface
THICKNESS = 50.0                      # m, normal to the sliding surface
TOE_FACE_START = 790.0                # x where the ground leaves the lower segment for the toe face
PLATEAU, VALLEY = 100.0, 200.0        # m of flat ground behind the crown and beyond the toe
LEVEL = 40.0                          # m, reservoir level (valley floor 0; the kink is at 49 m)
SPACING = 50.0                        # m, vertical joints, one through the kink
KINK_BLOCK = 3.0                      # m, width of the thin block just above the kink (docs/case-format.md)
DENSITY, YOUNG, POISSON = 2500.0, 10e9, 0.25
SLIDING_PHI, SLIDING_C = 18.0, 100e3  # sliding surface (c: limit equilibrium has the slope hold)
INTERNAL_PHI = 40.0


def sliding_surface():
    """Crown, kink and toe of the sliding surface (unrounded, so the dips are exact)."""
    y_kink = (X_TOE - X_KINK) * math.tan(math.radians(LOWER_DIP))
    y_crown = y_kink + X_KINK * math.tan(math.radians(UPPER_DIP))
    return [[0.0, y_crown], [X_KINK, y_kink], [X_TOE, 0.0]]


def ground():
    """Plateau, ground THICKNESS above the sliding surface (normal to it) on both segments, toe face,
    valley floor. The crown lies on the plateau: the slide tapers to it as the slope face rises."""
    (xc, yc), (xk, yk), (xt, yt) = sliding_surface()
    tu, tl = math.tan(math.radians(UPPER_DIP)), math.tan(math.radians(LOWER_DIP))
    hu = THICKNESS / math.cos(math.radians(UPPER_DIP))   # vertical thickness, upper segment
    hl = THICKNESS / math.cos(math.radians(LOWER_DIP))   # lower segment
    x_crest = xc + hu / tu                                 # the 30 deg ground line meets the plateau
    x_bend = xk + (hu - hl) / (tu - tl)                    # the two offset lines meet
    y_bend = yk + hu - tu * (x_bend - xk)
    y_face = yk - tl * (TOE_FACE_START - xk) + hl
    return [[xc - PLATEAU, yc], [x_crest, yc], [x_bend, y_bend], [TOE_FACE_START, y_face], [xt, yt],
            [xt + VALLEY, yt]]


def inside(x, frac):
    """A point at x, frac of the way from the sliding surface up to the ground."""
    ys, yg = value_at(sliding_surface(), x, "right"), value_at(ground(), x, "right")
    return [x, round(ys + frac * (yg - ys), 3)]


def make_case():
    """The case as a dict (docs/case-format.md, section form); the description quotes the limit
    equilibrium of the case's own slices."""
    (xc, yc), (xk, yk), (xt, _) = sliding_surface()
    case = {
        "description": "",
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": DENSITY, "young_modulus": YOUNG, "poisson_ratio": POISSON}},
        "joints": {
            "sliding_surface": {"friction_angle": SLIDING_PHI, "cohesion": SLIDING_C},
            "internal": {"friction_angle": INTERNAL_PHI, "cohesion": 0},
        },
        "default_joint": "internal",
        "section": {
            "ground": ground(),
            "sliding_surface": sliding_surface(),
            "base_depth": 100,
            "material": "rock",
            "sliding_joint": "sliding_surface",
            "joint_sets": [{"angle": 90, "spacing": SPACING, "origin": [xk, yk]}],
            "kink_block_width": KINK_BLOCK,
        },
        "monitors": [
            {"id": "crest", "point": inside(75.0, 0.5)},     # second block below the crown
            {"id": "middle", "point": inside(xk - 25, 0.5)},  # last block of the 30 deg segment
            {"id": "toe", "point": inside(xt - 35, 0.4)},     # the toe wedge, under water
        ],
        "water": {"level": LEVEL},
        "analysis": {"duration": 6.0},
        "expected": [
            {"monitor": "crest", "quantity": "displacement", "at_most": 0.1,
             "source": "Spencer on the same slices: critical c 66.2 kPa < 100 kPa, so the slide stands; "
                       "the 0.1 m bound leaves room for its settlement under gravity (4 cm, measured)"},
            {"monitor": "toe", "quantity": "displacement", "at_most": 0.01,
             "source": "the toe buttress does not move when the slide stands (limit equilibrium)"}],
    }
    slices = section_slices(case)
    tan_phi = math.tan(math.radians(SLIDING_PHI))
    c_hi = critical_cohesion(slices, tan_phi, 0.0)
    c_lo = critical_cohesion(slices, tan_phi, math.tan(math.radians(INTERNAL_PHI)))
    c_single = max(single_block_cohesion(*s, tan_phi) for s in slices)
    case["description"] = (
        "Chair-shaped reservoir bedding slide: a SYNTHETIC TEST GEOMETRY, reconstructed, inspired by a "
        "reservoir bedding slide (issue #14), not a survey of one. Sliding surface along bedding dipping "
        f"{UPPER_DIP:g} deg from the crown to a kink at x = {xk:g} m and {LOWER_DIP:g} deg below it to the "
        f"toe at x = {xt:g} m; slide mass {THICKNESS:g} m thick normal to the surface, tapering to the crown "
        f"on a plateau and to the toe by a steep face; vertical internal joints every {SPACING:g} m through "
        f"the kink (the kink cut is one of them). Reservoir at y = {LEVEL:g} m (valley floor 0) submerges the "
        f"toe. Rock {DENSITY:g} kg/m3, E {YOUNG / 1e9:g} GPa, nu {POISSON:g} (assumed). Internal joints phi "
        f"{INTERNAL_PHI:g} deg, c 0; sliding surface phi {SLIDING_PHI:g} deg, c {SLIDING_C / 1e3:g} kPa. "
        "Multi-wedge limit equilibrium of the vertical slices at that phi gives a critical c of "
        f"{c_hi / 1e3:.1f} kPa (interfaces without friction) to {c_lo / 1e3:.1f} kPa (interface friction "
        f"{INTERNAL_PHI:g} deg), so by limit equilibrium the slope holds, while a block of the "
        f"{UPPER_DIP:g} deg segment alone needs {c_single / 1e3:.1f} kPa: the flatter toe buttresses the "
        "upper blocks. Spencer's method on the same slices: "
        f"{spencer.critical_cohesion(spencer.case_slices(case), tan_phi)[0] / 1e3:.1f} kPa "
        f"(scripts/spencer.py cases/chair_slide.json --friction {SLIDING_PHI:g}). A {KINK_BLOCK:g} m kink block "
        "(section.kink_block_width) sits just above the kink: without it the 50 m block there leans on its corner "
        "at the kink, which slices cannot, and DDA's critical c falls to 17.4 kPa (docs/calibration.md). With it "
        "and softening joints (the default), DDA's critical c is 46.15 kPa, above the least c for which any contact "
        "forces hold these blocks (44.1 kPa, scripts/block_equilibrium.py); with brittle bonds (weakening_distance 0, "
        "original DDA) each upper block loses its bond as it slips and the answer is set by a single block, "
        "260 kPa (calibration/chair_slide). Multi-wedge limit equilibrium: "
        f"scripts/chair_slide.py le --friction {SLIDING_PHI:g}. Regenerate: scripts/chair_slide.py case")
    return case


def write_case(path):
    with open(path, "w") as f:
        json.dump(make_case(), f, indent=2)
        f.write("\n")
    print(f"wrote {path}")


def single_block_cohesion(w_eff, beta, length, tan_phi):
    """Critical cohesion (Pa) of one slice alone on its base: c = W'(sin b - cos b tan phi) / L
    (no interface forces; negative: it holds without cohesion)."""
    return w_eff * (math.sin(beta) - math.cos(beta) * tan_phi) / length


def critical_cohesion(slices, tan_phi, tan_delta):
    """Cohesion (Pa) of the sliding surface at which the slices are just in equilibrium (0 if they
    hold without). The toe thrust falls strictly with c (by 1 / (n_y + tan(delta) n_x) per unit of
    c L on each slice), so bisection."""
    if toe_thrust(slices, tan_phi, tan_delta, 0.0) <= 0:
        return 0.0
    lo, hi = 0.0, 1e5
    while toe_thrust(slices, tan_phi, tan_delta, hi) > 0:
        lo, hi = hi, 2 * hi
    for _ in range(100):
        mid = (lo + hi) / 2
        if toe_thrust(slices, tan_phi, tan_delta, mid) > 0:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def report_cohesion(case, slices, phi, deltas):
    """Print the critical cohesion for each delta and the single-block values."""
    tan_phi = math.tan(math.radians(phi))
    print(f"{len(slices)} slices, sliding-surface friction {phi:g} deg, water level "
          f"{case.get('water', {}).get('level')} m")
    for d in deltas:
        c = critical_cohesion(slices, tan_phi, math.tan(math.radians(d)))
        print(f"  interface friction {d:g} deg: critical cohesion {c / 1e3:.2f} kPa")
    print("  each slice alone (x from crown; W' effective weight; base dip; critical c, <= 0 holds):")
    x = case["section"]["sliding_surface"][0][0]
    singles = []
    for i, (w, beta, length) in enumerate(slices, 1):
        dx = length * math.cos(beta)
        c1 = single_block_cohesion(w, beta, length, tan_phi)
        singles.append(c1)
        print(f"    {i:2d} x {x:6.1f}-{x + dx:6.1f}  W' {w / 1e6:7.2f} MN/m  dip {math.degrees(beta):5.2f}  "
              f"c {c1 / 1e3:8.2f} kPa")
        x += dx
    print(f"  largest single-block critical cohesion: {max(singles) / 1e3:.2f} kPa")


def report_friction(case, slices, cohesion, deltas):
    """Print the critical friction at a given cohesion for each delta."""
    print(f"{len(slices)} slices, sliding-surface cohesion {cohesion / 1e3:g} kPa, water level "
          f"{case.get('water', {}).get('level')} m")
    for d in deltas:
        phi = critical_friction(slices, math.tan(math.radians(d)), cohesion)
        print(f"  interface friction {d:g} deg: critical friction {phi:.2f} deg")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    pc = sub.add_parser("case", help="write the case file")
    pc.add_argument("--out", default=CASE_PATH)
    pl = sub.add_parser("le", help="multi-wedge limit equilibrium with cohesion on the case's slices")
    pl.add_argument("--case", default=CASE_PATH)
    g = pl.add_mutually_exclusive_group(required=True)
    g.add_argument("--friction", type=float, help="sliding-surface friction (deg): solve for cohesion")
    g.add_argument("--cohesion", type=float, help="sliding-surface cohesion (Pa): solve for friction")
    pl.add_argument("--delta", type=float, action="append",
                    help="interface friction (deg), repeatable; default: 0 and the internal joints' friction")
    a = ap.parse_args()
    if a.command == "case":
        write_case(a.out)
        return
    case = json.load(open(a.case))
    deltas = a.delta or [0.0, case["joints"][case["default_joint"]]["friction_angle"]]
    slices = section_slices(case)
    if a.friction is not None:
        report_cohesion(case, slices, a.friction, deltas)
    else:
        report_friction(case, slices, a.cohesion, deltas)


if __name__ == "__main__":
    main()
