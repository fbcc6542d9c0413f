#!/usr/bin/env python3
"""Goodman & Bray (1976) limit equilibrium for block toppling, on the exact blocks ddaslope cuts.

The classic method assumes rectangular columns on a stepped base. This version takes the
polygons of `ddaslope cut CASE --out DIR` (DIR/blocks.json) as they are: columns bounded by
joints of one set, resting on one straight basal joint. Working from the top column down, each
column either stays, topples about its downslope base corner or slides on its base, and passes a
thrust P to the next (Goodman & Bray's P_t and P_s, written for general polygons: the interface
forces act at the top of each shared joint, friction P tan(phi) on the sides, sign as in their
derivation). The slope is stable when the toe column needs no support (P_0 <= 0). The factor of
safety is the F at which tan(phi)/F on every joint brings P_0 to zero (bisection).

Run: python3 scripts/toppling_limit_equilibrium.py DIR/blocks.json --joint-angle 64 --phi 31
"""
import argparse
import json
import math
import sys


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def area_centroid(poly):
    a = cx = cy = 0.0
    for i in range(len(poly)):
        p, q = poly[i], poly[(i + 1) % len(poly)]
        w = cross(p, q)
        a += w
        cx += (p[0] + q[0]) * w
        cy += (p[1] + q[1]) * w
    a /= 2
    return abs(a), (cx / (6 * a), cy / (6 * a))


def on_line(p, q, r, tol=1e-6):
    """True if r lies on the line through p and q."""
    d = sub(q, p)
    return abs(cross(d, sub(r, p))) <= tol * math.hypot(*d) * max(1.0, math.hypot(*sub(r, p)))


def on_segment(p, q, r, tol=1e-6):
    return on_line(p, q, r, tol) and min(p[0], q[0]) - tol <= r[0] <= max(p[0], q[0]) + tol


def basal_direction(blocks):
    """Unit vector down the straight basal joint: through the free blocks' vertices that lie on
    the fixed base's boundary, from the highest-left to the lowest-right."""
    base = [tuple(v) for v in next(b for b in blocks if b.get("fixed"))["vertices"]]
    edges = [(base[k], base[(k + 1) % len(base)]) for k in range(len(base))]
    on_base = sorted({tuple(v) for b in blocks if not b.get("fixed") for v in b["vertices"]
                      if any(on_segment(p, q, tuple(v)) for p, q in edges)})
    p0, p1 = on_base[0], on_base[-1]
    length = math.hypot(*sub(p1, p0))
    return ((p1[0] - p0[0]) / length, (p1[1] - p0[1]) / length)


def columns(blocks, base_dir):
    """Free blocks ordered from the top (upslope) to the toe, each with its base corners
    (upslope O_up, downslope O) and the tops of its upslope and downslope joints."""
    out = []
    for b in blocks:
        if b.get("fixed"):
            continue
        poly = [tuple(v) for v in b["vertices"]]
        # The base edge is the edge most nearly parallel to the basal joint and lowest.
        best = None
        for i in range(len(poly)):
            p, q = poly[i], poly[(i + 1) % len(poly)]
            e = sub(q, p)
            L = math.hypot(*e)
            if L < 1e-9:
                continue
            par = abs(cross(e, base_dir)) / L
            if par < 1e-3 and (best is None or p[1] + q[1] < best[2]):
                best = (i, (i + 1) % len(poly), p[1] + q[1])
        if best is None:  # a wedge touching the base in a single point: no column
            continue
        i, j, _ = best
        p, q = poly[i], poly[j]
        o_up, o = (p, q) if (q[0] - p[0]) * base_dir[0] + (q[1] - p[1]) * base_dir[1] > 0 else (q, p)
        area, g = area_centroid(poly)
        out.append({"id": b["id"], "poly": poly, "O_up": o_up, "O": o, "area": area, "G": g})
    out.sort(key=lambda c: c["O"][0] * base_dir[0] + c["O"][1] * base_dir[1])
    return out


def joint_top(poly, corner, d):
    """The vertex farthest from `corner` along direction d on the joint through `corner`."""
    best, far = corner, 0.0
    for v in poly:
        r = sub(v, corner)
        if abs(cross(d, r)) < 1e-6 * max(1.0, math.hypot(*r)):
            s = r[0] * d[0] + r[1] * d[1]
            if s > far:
                best, far = v, s
    return best, far


def toe_thrust(cols, unit_weight, joint_angle, base_angle, tan_phi, tan_base=None, trace=None):
    """P_0: the force the toe would need to stay in equilibrium (Goodman & Bray)."""
    d = (math.cos(math.radians(joint_angle)), math.sin(math.radians(joint_angle)))  # up the joint
    m = (d[1], -d[0])  # joint normal pointing downslope (from a column into its lower neighbour)
    t = (math.cos(math.radians(base_angle)), -math.sin(math.radians(base_angle)))  # down the base
    nb = (-t[1], t[0])  # base normal, up
    tan_base = tan_phi if tan_base is None else tan_base
    P = 0.0
    for c in cols:
        O, poly = c["O"], c["poly"]
        W = unit_weight * c["area"]
        A, _ = joint_top(poly, c["O_up"], d)
        B, L = joint_top(poly, O, d)
        f_up = (P * m[0] - tan_phi * P * d[0], P * m[1] - tan_phi * P * d[1])
        w = (0.0, -W)
        g = (-m[0] + tan_phi * d[0], -m[1] + tan_phi * d[1])  # per unit P_{n-1}
        # Toppling about O: moments of everything about O vanish.
        known = cross(sub(A, O), f_up) + cross(sub(c["G"], O), w)
        arm = cross(sub(B, O), g)
        p_topple = -known / arm if L > 1e-9 and arm > 0 else -math.inf
        # Sliding on the base with friction at its limit: P_{n-1} g + R (nb - tan t) = -(f_up + w).
        r = (nb[0] - tan_base * t[0], nb[1] - tan_base * t[1])
        rhs = (-(f_up[0] + w[0]), -(f_up[1] + w[1]))
        det = cross(g, r)
        p_slide = cross(rhs, r) / det
        P_next = max(p_topple, p_slide, 0.0)
        mode = "stable" if P_next == 0.0 else ("topples" if p_topple >= p_slide else "slides")
        if trace is not None:
            trace.append((c["id"], mode, p_topple, p_slide, P_next))
        P = P_next
    return P


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("blocks")
    ap.add_argument("--joint-angle", type=float, required=True, help="joint set angle, degrees ccw from +x")
    ap.add_argument("--phi", type=float, required=True, help="friction angle of every joint, degrees")
    ap.add_argument("--base-phi", type=float, help="friction angle of the basal joint (default: --phi), held fixed "
                    "while the other joints are reduced")
    ap.add_argument("--unit-weight", type=float, default=25000.0, help="rock unit weight, N/m^3")
    args = ap.parse_args()
    with open(args.blocks) as f:
        blocks = json.load(f)["blocks"]
    base_dir = basal_direction(blocks)
    base_angle = -math.degrees(math.atan2(base_dir[1], base_dir[0]))
    cols0 = columns(blocks, base_dir)
    tan0 = math.tan(math.radians(args.phi))
    trace = []
    tan_b = None if args.base_phi is None else math.tan(math.radians(args.base_phi))
    p_toe = toe_thrust(cols0, args.unit_weight, args.joint_angle, base_angle, tan0, tan_b, trace)
    print(f"basal joint at {base_angle:.3f} deg, {len(cols0)} columns, joints at {args.joint_angle} deg")
    print("column,mode,P_topple_N,P_slide_N,P_passed_N")
    for row in trace:
        print(f"{row[0]},{row[1]},{row[2]:.1f},{row[3]:.1f},{row[4]:.1f}")
    print(f"thrust needed at the toe with phi = {args.phi}: {p_toe:.1f} N/m")
    # Goodman & Bray's sliding thrust divides by 1 - tan^2(phi): the search keeps phi below 45 deg.
    lo, hi = tan0 * 1.0001, 5.0
    f = lambda F: toe_thrust(cols0, args.unit_weight, args.joint_angle, base_angle, tan0 / F, tan_b)
    if f(lo) > 0 or f(hi) <= 0:
        print(f"factor of safety outside [{lo:.3f}, {hi}]", file=sys.stderr)
        return 1
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) <= 0 else (lo, mid)
    F = 0.5 * (lo + hi)
    print(f"limit-equilibrium factor of safety: {F:.4f} (critical phi {math.degrees(math.atan(tan0 / F)):.2f} deg)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
