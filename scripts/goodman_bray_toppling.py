#!/usr/bin/env python3
"""Goodman & Bray (1976) limit equilibrium of block toppling on a stepped base: a referee for
cases/goodman_bray_toppling.json, written from the published equations (not from ddaslope).

Sources
  Goodman, R.E. & Bray, J.W. (1976) Toppling of rock slopes. Proc. ASCE Specialty Conference on
    Rock Engineering for Foundations and Slopes, Boulder, vol. 2, 201-234.
  Hoek, E. & Bray, J.W. (1981) Rock Slope Engineering, 3rd ed., IMM London, ch. 10 (worked example).
  Wyllie, D.C. & Mah, C.W. (2004) Rock Slope Engineering: Civil and Mining, 4th ed., Spon, ch. 9
    (sec. 9.4: limit equilibrium analysis of toppling on a stepped base, its worked example, and
    the toe-anchor equations; ch. 10 there is numerical analysis).

The book's example (the defaults here): slope height H = 92.5 m, face 56.6 deg, upper slope 4 deg,
overall (stepped) base 35.8 deg; base steps dip psi_p = 30 deg and the joints are normal to them
(dipping 60 deg into the slope); column width dx = 10 m; a1 = 5.0 m, a2 = 5.2 m, b = 1.0 m
(the book's rounded constants: a1 = dx tan(psi_f - psi_p), a2 = dx tan(psi_p - psi_s),
b = dx tan(psi_b - psi_p)); 16 columns, the crest column n = 10; heights
y_n = n (a1 - b) up to the crest (4, 8, ..., 40 m), then y_n = y_{n-1} - a2 - b (33.8, 27.6, 21.4,
15.2, 9.0, 2.8 m); unit weight 25 kN/m3; one friction angle phi on the column faces and the bases.

Method (Hoek & Bray 1981, eqs. for the stepped base; Wyllie & Mah 2004 eqs. 9.x), worked from
the top column n = 16 down to the toe n = 1. Column n carries W_n = gamma y_n dx, receives P_n from
above (normal to the joint, with friction Q_n = P_n tan phi) and needs P_{n-1} from below:
  toppling about its downslope base corner:
    P_{n-1,t} = [P_n (M_n - dx tan phi) + W_n/2 (y_n sin psi_p - dx cos psi_p)] / L_n
  sliding on its base:
    P_{n-1,s} = P_n - W_n (tan phi cos psi_p - sin psi_p) / (1 - tan^2 phi)
  with M_n = y_n, L_n = y_n - a1 below the crest; M_n = y_n - a2, L_n = y_n - a1 at the crest;
  M_n = y_n - a2, L_n = y_n above it. A column whose y_n / dx < cot psi_p and whose base holds
  (phi > psi_p) and that receives no thrust is stable (P_{n-1} = 0). Otherwise P_{n-1} is the larger
  of P_{n-1,t} and P_{n-1,s}, which names the mode. (--sticky-sliding: once a column slides, every
  column below it is taken to slide, as some implementations do; same numbers for this example.)
  P_0 is the force the toe needs. The slope is at limiting equilibrium when P_0 = 0; F is the
  divisor of tan(phi) that brings P_0 to 0 (Goodman & Bray's F on tan phi).

The toe support. Two conventions, both printed:
  (1) P_0 of the chain: a thrust on the toe column's downslope face, normal to it (parallel to
      the base steps, up-dip at psi_p above horizontal, into the slope), WITH the face friction
      P_0 tan phi that every interface force carries (Goodman & Bray's support force).
  (2) T: a pure force (an anchor or a point load, no shear on the face) at angle theta to the base
      direction (default 0: parallel to the base steps, normal to the toe face), applied on the toe
      face at height h (default y_1 / 2). T is the least force that holds the toe column against
      both sliding and toppling given P_1 from the column above (Wyllie & Mah's anchor equations,
      here for any theta): sliding
        T = [P_1 (1 - tan^2 phi) - W_1 (tan phi cos psi_p - sin psi_p)] / (cos theta + tan phi sin theta),
      with theta > 0 turning T into the base (more normal force); toppling needs the moment of T
      about the toe corner. This is the force a DDA point load must carry.

Run:  python3 scripts/goodman_bray_toppling.py               # the book's example
      python3 scripts/goodman_bray_toppling.py --phi 33.02 --table
      python3 scripts/goodman_bray_toppling.py --theta 30 --toe-force 2013 \
          --write-case cases/goodman_bray_toppling.json   # the shipped case (horizontal force)
"""
import argparse
import math
import sys


DESCRIPTION = (
    "Goodman & Bray (1976) block toppling on a stepped base, the worked example of Hoek & Bray (Rock Slope "
    "Engineering, 3rd ed. 1981, ch. 10) and Wyllie & Mah (Rock Slope Engineering, 4th ed. 2004, sec. 9.4): "
    "slope 92.5 m high, face 56.6 deg, upper slope 4 deg, stepped base 35.8 deg overall; 16 columns dx = 10 m "
    "on base steps dipping 30 deg, joints normal to them (dip 60 deg into the slope), a1 = 5.0, a2 = 5.2, "
    "b = 1.0 m, heights 4, 8, ..., 40 (crest column 10), 33.8, 27.6, 21.4, 15.2, 9.0, 2.8 m; 25 kN/m3 "
    "(density 25000/9.81), E = 20 GPa, nu = 0.25. Published: limiting equilibrium without support at "
    "phi = 38.15 deg (python3 scripts/goodman_bray_toppling.py: 38.13 deg). Here phi = 33.02 deg on every "
    "surface (c = 0, no tension) with a horizontal support force of 2013 kN/m into the slope on the toe "
    "column (point load toe_force, at mid-height of its 4 m face). Goodman & Bray at 33.02 deg: columns 14-16 "
    "stand, 5-13 topple, 1-4 slide; a pure horizontal toe force of 1997 kN/m gives F = 1 (2013 kN/m: "
    "F = 1.001); parallel to the base steps 2379 kN/m would be needed; Goodman & Bray's own P_0, normal "
    "to the toe face and carrying face friction P_0 tan phi, is 4118 kN/m. Without the force F = "
    "tan 33.02/tan 38.13 = 0.828. ddaslope fos: 1.003 with the force, 0.825 without (--set "
    "point_loads[0].force[0]=0), 1.001 at phi = 38.15 without it. Try: ddaslope fos cases/goodman_bray_toppling.json, "
    "and the toe force for F = 1: ddaslope critical cases/goodman_bray_toppling.json --solve support --support toe_force"
)


def book_heights(n_cols=16, crest=10, a1=5.0, a2=5.2, b=1.0):
    y = [n * (a1 - b) for n in range(1, crest + 1)]
    while len(y) < n_cols:
        y.append(y[-1] - a2 - b)
    return y  # y[0]: the toe column n = 1


def chain(y, dx, psi_p, a1, a2, crest, unit_weight, tan_phi, sticky=False):
    """Goodman & Bray from the top column down. Returns (P_0, P_1, rows); rows top to toe:
    (n, y_n, W_n, mode, P_{n-1,t}, P_{n-1,s}, P_{n-1})."""
    s, c = math.sin(math.radians(psi_p)), math.cos(math.radians(psi_p))
    P, rows, sliding, P1 = 0.0, [], False, 0.0
    for n in range(len(y), 0, -1):
        yn = y[n - 1]
        W = unit_weight * yn * dx
        if n < crest:
            M, L = yn, yn - a1
        elif n == crest:
            M, L = yn - a2, yn - a1
        else:
            M, L = yn - a2, yn
        pt = (P * (M - dx * tan_phi) + 0.5 * W * (yn * s - dx * c)) / L if L > 0 and not sliding else -math.inf
        ps = P - W * (tan_phi * c - s) / (1.0 - tan_phi ** 2)
        if n == 1:
            P1 = P
        if max(pt, ps) <= 0.0:
            mode, Pn = "stable", (max(pt, ps) if n == 1 else 0.0)
        elif pt >= ps:
            mode, Pn = "topples", pt
        else:
            mode, Pn = "slides", ps
            sliding = sliding or sticky
        rows.append((n, yn, W, mode, pt, ps, Pn))
        P = Pn  # a stable column passes nothing on; at the toe the signed value is the margin
    return P, P1, rows


def toe_force(P1, y1, dx, psi_p, tan_phi, unit_weight, theta_deg=0.0, h=None):
    """Least pure force T on the toe column's downslope face (no face friction), at theta_deg from
    the up-dip base direction (positive: turned into the base), applied h up the face, that keeps
    the toe column from sliding and from toppling. Returns (T, T_slide, T_topple)."""
    s, c = math.sin(math.radians(psi_p)), math.cos(math.radians(psi_p))
    th = math.radians(theta_deg)
    h = 0.5 * y1 if h is None else h
    W = unit_weight * y1 * dx
    # Base frame: x up-dip along the base (into the slope), z along the joints (up). On the toe
    # column: W; P_1 from column 2 on its upslope face (down-dip) with Q_1 = P_1 tan phi towards the
    # base (Goodman & Bray's signs: R_n = W_n cos psi_p + (P_n - P_{n-1}) tan phi); T with an
    # up-dip part T cos theta and a part T sin theta into the base; no shear on the toe face.
    #   normal:           R = W c + P_1 tan phi + T sin theta
    #   down-dip, limit:  W s + P_1 = R tan phi + T cos theta
    # => T (cos theta + tan phi sin theta) = P_1 (1 - tan^2 phi) + W (s - c tan phi)
    # For theta = 0 this is P_{0,s} (1 - tan^2 phi): the face friction P_0 tan phi of the chain's
    # P_0 is what makes the two differ.
    T_slide = (P1 * (1 - tan_phi ** 2) + W * (s - c * tan_phi)) / (math.cos(th) + tan_phi * math.sin(th))
    # Toppling about the toe corner O (x up-dip from O, z up the face): W at (dx/2, y_1/2); P_1 at
    # z = M_1 = y_1 (column 2 is taller), Q_1 at x = dx towards the base; T at (0, h), so only its
    # up-dip part has an arm.
    drive = 0.5 * W * (y1 * s - dx * c) + P1 * (y1 - dx * tan_phi)
    arm = math.cos(th) * h
    T_topple = drive / arm if arm > 0 else (math.inf if drive > 0 else -math.inf)
    return max(T_slide, T_topple, 0.0), T_slide, T_topple


def factor_with_support(run, y1, dx, psi_p, tan_phi, unit_weight, T, theta_deg, h):
    """Goodman & Bray's F (the divisor of tan phi on every surface) of the slope with the pure toe
    force T (kN/m) held: the largest F at which T still suffices."""
    need = lambda F: toe_force(run(tan_phi / F)[1], y1, dx, psi_p, tan_phi / F, unit_weight, theta_deg, h)[0]
    lo, hi = 0.2, 3.0
    if need(lo) > T:
        return float("nan")
    if need(hi) <= T:
        return hi
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if need(mid) <= T else (lo, mid)
    return 0.5 * (lo + hi)


def to_world(X, Y, psi_p):
    """Base frame (X up-dip along the base steps, Y along the joints) to the case's frame: the
    steps dip psi_p towards +x (the slope faces +x, the toe corner at the origin), gravity -y."""
    s, c = math.sin(math.radians(psi_p)), math.cos(math.radians(psi_p))
    return [round(-X * c + Y * s, 9), round(X * s + Y * c, 9)]


def case(y, dx, psi_p, b, crest, unit_weight, phi, T, theta_deg, h, published):
    """The ddaslope case: the columns as rectangles, one fixed base whose top is the staircase
    (a step of base plane beyond the toe, so that the toe column can slide out, and one beyond the
    top column), the pure toe force T (kN/m) at theta_deg from the up-dip base direction."""
    n = len(y)
    w = lambda X, Y: to_world(X, Y, psi_p)
    cols = []
    for k in range(1, n + 1):
        X0, Y0 = (k - 1) * dx, (k - 1) * b
        cols.append({"id": f"column_{k}", "material": "rock",
                     "vertices": [w(X0, Y0), w(X0 + dx, Y0), w(X0 + dx, Y0 + y[k - 1]), w(X0, Y0 + y[k - 1])]})
    top = [w(-dx, 0.0)]
    for k in range(1, n + 1):
        top += [w((k - 1) * dx, (k - 1) * b), w(k * dx, (k - 1) * b)]
    top += [w(n * dx, n * b), w((n + 1) * dx, n * b)]
    bottom = round(min(p[1] for p in top) - 20.0, 9)
    base = top + [[top[-1][0], bottom], [top[0][0], bottom]]
    ang = math.radians(psi_p - theta_deg)
    force = [round(-T * 1e3 * math.cos(ang), 1), round(T * 1e3 * math.sin(ang), 1)]
    if abs(force[1]) < 0.05:
        force[1] = 0.0
    return {
        "description": published,
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": round(unit_weight * 1e3 / 9.81, 5), "young_modulus": 2e10, "poisson_ratio": 0.25}},
        "joints": {"joint": {"friction_angle": phi, "cohesion": 0, "tensile_strength": 0}},
        "default_joint": "joint",
        "blocks": [{"id": "base", "material": "rock", "fixed": True, "vertices": base}] + cols,
        "point_loads": [{"id": "toe_force", "block": "column_1", "point": w(0.0, h), "force": force}],
        "monitors": [
            {"id": "toe", "block": "column_1", "point": w(0.5 * dx, 0.5 * y[0])},
            {"id": "middle", "block": "column_7", "point": w(6.5 * dx, 6 * b + y[6] - 1.0)},
            {"id": "crest", "block": f"column_{crest}", "point": w((crest - 0.5) * dx, (crest - 1) * b + y[crest - 1] - 1.0)},
            {"id": "top", "block": f"column_{n}", "point": w((n - 0.5) * dx, (n - 1) * b + 0.5 * y[n - 1])},
        ],
        # 0.5 m, as cases/stepped_toppling.json: trials near F = 1 lean a few cm and stop
        "analysis": {"duration": 2.0, "time_step": 0.001, "failure_displacement": 0.5},
        "expected": [{"monitor": "top", "quantity": "displacement", "at_most": 0.01,
                      "source": "Goodman & Bray: columns 14-16 stand (no thrust from above, y/dx < cot 30 deg); "
                                "measured 4e-5 m"}],
    }


def limit_phi(P0_of_tan, lo_deg=20.0, hi_deg=44.9):
    """phi (deg) at which P_0 = 0, by bisection (P_0 falls as phi rises)."""
    lo, hi = lo_deg, hi_deg
    if P0_of_tan(math.tan(math.radians(lo))) <= 0 or P0_of_tan(math.tan(math.radians(hi))) > 0:
        raise ValueError("limiting phi outside [%g, %g] deg" % (lo_deg, hi_deg))
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if P0_of_tan(math.tan(math.radians(mid))) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--phi", type=float, default=33.02, help="joint friction angle for the toe force, deg (33.02)")
    ap.add_argument("--dx", type=float, default=10.0, help="column width, m (10)")
    ap.add_argument("--psi-p", type=float, default=30.0, help="dip of the base steps, deg (30)")
    ap.add_argument("--a1", type=float, default=5.0, help="Hoek & Bray's a1, m (5.0)")
    ap.add_argument("--a2", type=float, default=5.2, help="Hoek & Bray's a2, m (5.2)")
    ap.add_argument("--b", type=float, default=1.0, help="riser per column, m (1.0)")
    ap.add_argument("--crest", type=int, default=10, help="crest column number (10)")
    ap.add_argument("--heights", type=str, help="column heights y_1..y_n, m, comma separated "
                    "(default: the book's 4, 8, ..., 40, 33.8, ..., 2.8)")
    ap.add_argument("--unit-weight", type=float, default=25.0, help="kN/m3 (25)")
    ap.add_argument("--theta", type=float, default=0.0, help="direction of the pure toe force T, deg from the "
                    "up-dip base direction, positive into the base (0: parallel to the base, normal to the toe face)")
    ap.add_argument("--height", type=float, help="where T acts, m up the toe face from the toe corner (default y_1/2)")
    ap.add_argument("--toe-force", type=float, help="a pure toe force T held at this value, kN/m: prints the F it "
                    "gives at --phi (direction --theta, height --height)")
    ap.add_argument("--write-case", metavar="PATH", help="write the ddaslope case (columns, base, the toe "
                    "force --toe-force or else the T found, at --theta and --height) to PATH")
    ap.add_argument("--anchor-case", metavar="PATH", help="write the case held by a toe anchor instead (a "
                    "support element at --theta, 12 m long into the base, holding the toe force as its pretension)")
    ap.add_argument("--sticky-sliding", action="store_true", help="once a column slides, all below slide")
    ap.add_argument("--table", action="store_true", help="print the column-by-column table")
    args = ap.parse_args()

    y = [float(v) for v in args.heights.split(",")] if args.heights else book_heights(16, args.crest, args.a1, args.a2, args.b)
    g = args.unit_weight
    run = lambda t: chain(y, args.dx, args.psi_p, args.a1, args.a2, args.crest, g, t, args.sticky_sliding)
    print(f"{len(y)} columns, dx = {args.dx} m, base steps psi_p = {args.psi_p} deg, joints normal to them "
          f"(dip {90 - args.psi_p:g} deg into the slope), a1 = {args.a1}, a2 = {args.a2}, b = {args.b} m, "
          f"crest column {args.crest}, gamma = {g} kN/m3")
    print("heights y_1..y_n (m): " + ", ".join(f"{v:g}" for v in y))
    print(f"overall base angle: {math.degrees(math.atan2(len(y) * args.b * math.cos(math.radians(args.psi_p)) + len(y) * args.dx * math.sin(math.radians(args.psi_p)), len(y) * args.dx * math.cos(math.radians(args.psi_p)) - len(y) * args.b * math.sin(math.radians(args.psi_p)))):.2f} deg")

    phi_lim = limit_phi(lambda t: run(t)[0])
    print(f"(a) friction angle for limiting equilibrium without support (P_0 = 0): {phi_lim:.3f} deg")
    tan_phi = math.tan(math.radians(args.phi))
    P0, P1, rows = run(tan_phi)
    F = math.tan(math.radians(args.phi)) / math.tan(math.radians(phi_lim))
    print(f"    at phi = {args.phi} deg without support: F = tan {args.phi} / tan {phi_lim:.3f} = {F:.4f}")
    if args.table:
        print(f"phi = {args.phi} deg: column, y_n m, W_n kN/m, mode, P_(n-1),t kN/m, P_(n-1),s kN/m, P_(n-1) kN/m")
        for n, yn, W, mode, pt, ps, Pn in rows:
            fmt = lambda v: "-" if v == -math.inf else f"{v:.1f}"
            print(f"  {n:2d} {yn:5.1f} {W:8.1f} {mode:8s} {fmt(pt):>10s} {fmt(ps):>10s} {Pn:10.1f}")
    T, Ts, Tt = toe_force(P1, y[0], args.dx, args.psi_p, tan_phi, g, args.theta, args.height)
    h = 0.5 * y[0] if args.height is None else args.height
    print(f"(b) toe support at phi = {args.phi} deg (P_1 from column 2 = {P1:.1f} kN/m):")
    print(f"    (1) Goodman & Bray P_0 (normal to the toe face, up-dip at {args.psi_p:g} deg above horizontal, "
          f"with face friction P_0 tan phi): {P0:.1f} kN/m")
    print(f"    (2) pure force T at {args.theta:g} deg from the up-dip base direction "
          f"({args.psi_p - args.theta:g} deg above horizontal, into the slope), {h:g} m up the toe face: "
          f"T = {T:.1f} kN/m (sliding needs {Ts:.1f}, toppling {Tt:.1f})")
    for th in (0.0, args.psi_p, math.degrees(math.atan(tan_phi))):
        Tx = toe_force(P1, y[0], args.dx, args.psi_p, tan_phi, g, th, args.height)[0]
        print(f"        T at {th:5.2f} deg from the base direction ({args.psi_p - th:5.2f} deg above horizontal): {Tx:.1f} kN/m")
    if args.toe_force is not None:
        Fs = factor_with_support(run, y[0], args.dx, args.psi_p, tan_phi, g, args.toe_force, args.theta, args.height)
        print(f"(c) with T = {args.toe_force:g} kN/m held at {args.theta:g} deg from the base direction: "
              f"Goodman & Bray F = {Fs:.4f} (critical phi {math.degrees(math.atan(tan_phi / Fs)):.3f} deg)")
    if args.write_case:
        import json
        Tc = args.toe_force if args.toe_force is not None else T
        doc = case(y, args.dx, args.psi_p, args.b, args.crest, g, args.phi, Tc, args.theta, h, DESCRIPTION)
        with open(args.write_case, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
        print(f"wrote {args.write_case}: toe force {doc['point_loads'][0]['force']} N/m at {doc['point_loads'][0]['point']}")
    if args.anchor_case:
        import json
        Tc = args.toe_force if args.toe_force is not None else T
        doc = case(y, args.dx, args.psi_p, args.b, args.crest, g, args.phi, Tc, args.theta, h, DESCRIPTION)
        load = doc.pop("point_loads")[0]
        head = load["point"]
        unit = [c / math.hypot(*load["force"]) for c in load["force"]]
        end = [round(head[0] + 12.0 * unit[0], 6), round(head[1] + 12.0 * unit[1], 6)]
        doc["supports"] = [{"id": "toe_anchor", "head": head, "head_block": "column_1", "end": end,
                            "end_block": "base", "pretension": round(Tc * 1e3, 1)}]
        doc["description"] = (
            f"The Goodman & Bray toppling slope of cases/goodman_bray_toppling.json (phi = {args.phi:g} deg, F = 0.828 "
            f"unsupported) held by a toe anchor: a support element from mid-height of the toe column's face, "
            f"{args.psi_p - args.theta:g} deg above the horizontal (into the slope and down), 12 m into the rock "
            f"below, holding {Tc:.1f} kN/m (its pretension, no stiffness: a constant force). Goodman & Bray's chain "
            f"with a pure toe force in that direction (python3 scripts/goodman_bray_toppling.py --theta "
            f"{args.theta:g}): {T:.1f} kN/m for limiting equilibrium. Try: ddaslope critical "
            f"cases/goodman_bray_toppling_anchor.json --solve support --support toe_anchor (docs/supports.md)")
        with open(args.anchor_case, "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
        print(f"wrote {args.anchor_case}: toe anchor from {head} to {end}, {Tc:.1f} kN/m")
    ang = math.radians(args.psi_p - args.theta)  # the slope faces +x: up-dip is (-cos psi_p, sin psi_p)
    print(f"    T as a vector for a slope facing +x (toe at the right, slope rising to the left): "
          f"[{-T * math.cos(ang) * 1e3:.0f}, {T * math.sin(ang) * 1e3:.0f}] N/m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
