#!/usr/bin/env python3
"""Block toppling on a stepped base: Hoek & Bray's worked example, its Goodman & Bray limit
equilibrium, and the ddaslope case built from the same blocks.

Hoek & Bray (1981, Rock Slope Engineering, 3rd ed., ch. 10; also Wyllie & Mah 2004, sec. 7.3):
16 rectangular columns of width dx = 10 m along a base plane dipping psi_p = 30 deg, cut by
joints normal to it (dipping 60 deg into the slope). The base rises by b = 1 m per column (a
riser along the joints: the overall base dips 35.8 deg). Heights y_n = n (a1 - b) up to the
crest column (n = 10), then y_n = y_(n-1) - a2 - b, with a1 = 5.0 m, a2 = 5.2 m. With one
friction angle on every surface the slope is at limiting equilibrium (F = 1) at phi = 38.15 deg:
the upper three columns stand, the next seven topple, the three at the toe slide.

    python3 scripts/stepped_toppling.py fos [--phi 38.15]     # Goodman & Bray F and modes
    python3 scripts/stepped_toppling.py case > cases/stepped_toppling.json

In the case the columns are the same rectangles, turned so that gravity is vertical, on one
fixed base block whose top is the staircase (base segments and 1 m risers).
"""
import argparse
import json
import math
import sys

DX, B, A1, A2 = 10.0, 1.0, 5.0, 5.2  # m: column width, riser, Hoek & Bray's a1 and a2
PSI_P = 30.0                          # deg: dip of the base planes
N, CREST = 16, 10                     # columns; the crest column
UNIT_WEIGHT = 25000.0                 # N/m^3 (rho g with g = 9.81)


def heights():
    y = [n * (A1 - B) for n in range(1, CREST + 1)]
    while len(y) < N:
        y.append(y[-1] - A2 - B)
    return y  # y[0] is the toe column (n = 1)


def toe_thrust(tan_phi, trace=None):
    """P_0 of Goodman & Bray: the force the toe needs to stay in equilibrium, worked from the top
    column down with the interface forces at the top of the shorter column of each pair."""
    y = heights()
    s, c = math.sin(math.radians(PSI_P)), math.cos(math.radians(PSI_P))
    P, sliding = 0.0, False
    for n in range(N, 0, -1):
        yn = y[n - 1]
        W = UNIT_WEIGHT * yn * DX
        M = yn if n < CREST else yn - A2  # arm of P_n (upslope interface)
        L = yn - A1 if n <= CREST else yn  # arm of P_(n-1) (downslope interface)
        # Once a column slides every column below it slides too (Goodman & Bray); the toe
        # column's toppling arm y_1 - a1 is negative anyway.
        p_topple = -math.inf if sliding or L <= 0 else (P * (M - DX * tan_phi) + 0.5 * W * (yn * s - DX * c)) / L
        p_slide = P - W * (tan_phi * c - s) / (1 - tan_phi ** 2)
        P_next = max(p_topple, p_slide, 0.0)
        mode = "stable" if P_next == 0.0 else ("topples" if p_topple >= p_slide else "slides")
        sliding = sliding or mode == "slides"
        if trace is not None:
            trace.append((n, yn, mode, p_topple, p_slide, P_next))
        P = P_next
    return P if not sliding else p_slide  # the signed thrust: < 0 is a margin


def factor_of_safety(phi_deg):
    """The F at which tan(phi)/F on every surface brings P_0 to zero (bisection)."""
    tan0 = math.tan(math.radians(phi_deg))
    lo, hi = tan0 * 1.0001, 5.0  # tan(phi)/F < 1: the sliding formula divides by 1 - tan^2
    if toe_thrust(tan0 / lo) > 0 or toe_thrust(tan0 / hi) <= 0:
        raise ValueError("factor of safety outside [%.3f, %.1f]" % (lo, hi))
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if toe_thrust(tan0 / mid) <= 0 else (lo, mid)
    return 0.5 * (lo + hi)


def to_world(X, Y):
    """Base frame (X up the base plane, Y along the joints, away from the base) to the world
    frame, where the base planes dip PSI_P towards +x and gravity is -y. Origin: the toe."""
    s, c = math.sin(math.radians(PSI_P)), math.cos(math.radians(PSI_P))
    return [round(-X * c + Y * s, 9), round(X * s + Y * c, 9)]


def case(phi_deg):
    y = heights()
    columns = []
    for n in range(1, N + 1):
        x0, y0 = (n - 1) * DX, (n - 1) * B
        rect = [(x0, y0), (x0, y0 + y[n - 1]), (x0 + DX, y0 + y[n - 1]), (x0 + DX, y0)]
        columns.append({"id": f"column_{n}", "material": "rock", "vertices": [to_world(*p) for p in rect]})
    # The base: one column width of base plane beyond the toe (the toe column slides out along
    # it, as Goodman & Bray assume), the staircase under the columns, one width beyond the top.
    stairs = [(-DX, 0.0)]
    for n in range(1, N + 1):
        stairs += [((n - 1) * DX, (n - 1) * B), (n * DX, (n - 1) * B)]
    stairs += [(N * DX, N * B), ((N + 1) * DX, N * B)]
    top = [to_world(*p) for p in stairs]
    bottom = min(p[1] for p in top) - 20.0
    base = top + [[top[-1][0], bottom], [top[0][0], bottom]]
    monitors = [
        {"id": "toe", "block": "column_1", "point": to_world(0.5 * DX, 0.5 * y[0])},
        {"id": "crest", "block": f"column_{CREST}", "point": to_world((CREST - 0.5) * DX, (CREST - 1) * B + y[CREST - 1] - 1)},
        {"id": "upper", "block": "column_15", "point": to_world(14.5 * DX, 14 * B + 0.5 * y[14])},
    ]
    return {
        "description": (
            "Block toppling on a stepped base: Hoek & Bray's worked example (Rock Slope Engineering, 1981; "
            "Wyllie & Mah 2004, sec. 7.3), built by scripts/stepped_toppling.py. 16 columns 10 m wide on base "
            "planes dipping 30 deg, joints normal to them, the base rising by a 1 m riser per column; heights "
            "4 to 40 m (crest column 10) and down to 2.8 m. Every surface phi = %.2f deg, c = 0: Goodman & Bray "
            "limit equilibrium F = 1.00 (python3 scripts/stepped_toppling.py fos), columns 14-16 standing, 4-13 "
            "toppling, 1-3 sliding. Rock 25 kN/m3, E = 20 GPa, nu = 0.25. Try: ddaslope fos cases/stepped_toppling.json"
            % phi_deg),
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": round(UNIT_WEIGHT / 9.81, 6), "young_modulus": 2e10, "poisson_ratio": 0.25}},
        "joints": {"joint": {"friction_angle": phi_deg, "cohesion": 0, "tensile_strength": 0}},
        "default_joint": "joint",
        "blocks": [{"id": "base", "material": "rock", "fixed": True, "vertices": base}] + columns,
        "monitors": monitors,
        # 0.5 m: a toppling column's top has clearly left; trials that lean by 7 cm and stop
        # are not failure (the default 1e-3 w0 = 7.4 cm is their scale: docs/calibration.md).
        "analysis": {"duration": 2.0, "time_step": 0.001, "failure_displacement": 0.5},
        # At the limiting phi deformable DDA fails (F = 0.99-1.00) and rigid DDA holds (1.009), so
        # the case checks what holds either way: Goodman & Bray's standing columns stand.
        "expected": [
            {"monitor": "upper", "quantity": "displacement", "at_most": 0.01,
             "source": "Goodman & Bray at phi = 38.15 deg: columns 14-16 stand (y/dx < cot 30 deg, no thrust from above); "
                       "measured 4e-5 m deformable (the slope below topples), 3e-6 m rigid"},
        ],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=["fos", "case"])
    ap.add_argument("--phi", type=float, default=38.15, help="friction angle of every surface, degrees")
    args = ap.parse_args()
    if args.what == "case":
        json.dump(case(args.phi), sys.stdout, indent=1)
        print()
        return 0
    trace = []
    p0 = toe_thrust(math.tan(math.radians(args.phi)), trace)
    print("column,height_m,mode,P_topple_N,P_slide_N,P_passed_N")
    for n, yn, mode, pt, ps, pn in trace:
        print(f"{n},{yn:.1f},{mode},{pt:.0f},{ps:.0f},{pn:.0f}")
    print(f"thrust needed at the toe with phi = {args.phi}: {p0:.0f} N/m")
    F = factor_of_safety(args.phi)
    print(f"limit-equilibrium factor of safety: {F:.4f} "
          f"(critical phi {math.degrees(math.atan(math.tan(math.radians(args.phi)) / F)):.2f} deg)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
