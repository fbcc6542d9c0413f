#!/usr/bin/env python3
"""Limit-equilibrium check of a section case (docs/vajont.md): the friction angle of the sliding
surface (c = 0) at which the slide mass is just in equilibrium, by force equilibrium of vertical
slices (the multi-wedge method: slices joined by vertical interfaces whose shear is E tan(delta)).

The slices are those ddaslope cuts: vertical joints of the case's section (explicit joints and
joint sets at 90 deg), plus cuts at every break of the sliding surface. Water as in ddaslope:
hydrostatic pressure below the level on every face of a slice, so its net force is buoyancy and
the contact forces are effective forces. No moment equilibrium (as in the wedge method).
The sliding surface is frictional here (c = 0); toe_thrust also takes a cohesion on the slice bases,
which scripts/chair_slide.py uses.

Run: python3 scripts/vajont_limit_equilibrium.py cases/vajont.json [--delta 40] [--kinks-only]
"""
import argparse, json, math


def value_at(poly, x, side):
    """Height of polyline `poly` at x; side 'left'/'right' picks the limit at a vertical step."""
    for (x0, y0), (x1, y1) in zip(poly, poly[1:]):
        if x1 <= x0:
            continue
        if (side == "right" and x0 <= x < x1) or (side == "left" and x0 < x <= x1):
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    raise ValueError(f"x = {x} outside the polyline")


def positive_part_integral(x0, x1, f0, f1):
    """Integral over [x0, x1] of max(0, f) for f linear from f0 to f1."""
    if f0 >= 0 and f1 >= 0:
        return (x1 - x0) * (f0 + f1) / 2
    if f0 <= 0 and f1 <= 0:
        return 0.0
    xc = x0 + (x1 - x0) * f0 / (f0 - f1)  # where f crosses zero
    return (xc - x0) * f0 / 2 if f0 > 0 else (x1 - xc) * f1 / 2


def clipped_integral(x0, x1, g0, g1, s0, s1, level):
    """Integral of max(0, min(g, level) - s) over [x0, x1], g and s linear."""
    # Split where g crosses the level: on each part min(g, level) is linear.
    pieces = [(x0, g0, s0), (x1, g1, s1)]
    if (g0 - level) * (g1 - level) < 0:
        xc = x0 + (x1 - x0) * (g0 - level) / (g0 - g1)
        sc = s0 + (s1 - s0) * (xc - x0) / (x1 - x0)
        pieces.insert(1, (xc, level, sc))
    total = 0.0
    for (xa, ga, sa), (xb, gb, sb) in zip(pieces, pieces[1:]):
        total += positive_part_integral(xa, xb, min(ga, level) - sa, min(gb, level) - sb)
    return total


def slice_areas(ground, surface, xa, xb, level):
    """Area of the slice between xa and xb, and its area below the water level."""
    xs = sorted({xa, xb} | {x for x, _ in ground + surface if xa < x < xb})
    area = wet = 0.0
    for x0, x1 in zip(xs, xs[1:]):
        g0, g1 = value_at(ground, x0, "right"), value_at(ground, x1, "left")
        s0, s1 = value_at(surface, x0, "right"), value_at(surface, x1, "left")
        area += positive_part_integral(x0, x1, g0 - s0, g1 - s1)
        if level is not None:
            wet += clipped_integral(x0, x1, g0, g1, s0, s1, level)
    return area, wet


def toe_thrust(slices, tan_phi, tan_delta, cohesion=0.0):
    """Effective thrust the last slice would need from beyond the toe (> 0: the mass slides).

    slices: (effective weight, base dip beta[, base length]) from crown to toe; the base length is
    needed only with a cohesion c (Pa), which acts on each base as c * length, up the slope."""
    e = 0.0
    for w_eff, beta, *length in slices:
        # Base: normal N on the upward normal (sin b, cos b), shear N tan(phi) + C up the slope
        # (C = c * base length). Interfaces: E on the left face pushes +x and drags down by
        # E tan(delta) (the upslope slice moves down relative to this one); the right face's E'
        # pushes back -x and holds up. x: N nx - C cos b = E' - E; y: N ny + C sin b + (E' - E)
        # tan(delta) = W.
        c_force = cohesion * length[0] if cohesion else 0.0
        nx = math.sin(beta) - tan_phi * math.cos(beta)
        ny = math.cos(beta) + tan_phi * math.sin(beta)
        n = (w_eff - c_force * (math.sin(beta) - tan_delta * math.cos(beta))) / (ny + tan_delta * nx)
        e = max(0.0, e + n * nx - c_force * math.cos(beta))  # no tension across a joint
    return e


def slice_cuts(sec, kinks_only=False):
    """x of the slice boundaries: the sliding surface's ends and breaks, and (unless kinks_only) the
    section's vertical joints and 90-degree joint sets."""
    surface = sec["sliding_surface"]
    x_start, x_end = surface[0][0], surface[-1][0]
    cuts = {x for x, _ in surface[1:-1]}
    if not kinks_only:
        for j in sec.get("joints", []):
            if abs(j[0][0] - j[1][0]) < 1e-9:
                cuts.add(j[0][0])
        for js in sec.get("joint_sets", []):
            if js["angle"] == 90:
                x = js["origin"][0]
                while x > x_start:
                    x -= js["spacing"]
                while x < x_end:
                    if x > x_start:
                        cuts.add(x)
                    x += js["spacing"]
    return sorted({x_start, x_end} | {x for x in cuts if x_start < x < x_end})


def section_slices(case, kinks_only=False):
    """The case's slices from crown to toe: (effective weight N/m, base dip rad, base length m)."""
    sec = case["section"]
    ground, surface = sec["ground"], sec["sliding_surface"]
    xs = slice_cuts(sec, kinks_only)
    rho = case["materials"][sec["material"]]["density"] if "material" in sec \
        else next(iter(case["materials"].values()))["density"]
    g = -case.get("gravity", [0, -9.81])[1]
    gamma_w = case.get("water", {}).get("unit_weight", 9810.0)
    level = case.get("water", {}).get("level")
    slices = []
    for xa, xb in zip(xs, xs[1:]):
        area, wet = slice_areas(ground, surface, xa, xb, level)
        ya, yb = value_at(surface, xa, "right"), value_at(surface, xb, "left")
        beta = math.atan2(ya - yb, xb - xa)
        slices.append((rho * g * area - gamma_w * wet, beta, math.hypot(xb - xa, ya - yb)))
    return slices


def critical_friction(slices, tan_delta, cohesion=0.0):
    """Friction angle (deg) of the sliding surface at which the slices are just in equilibrium."""
    lo, hi = 0.0, 60.0  # phi (deg): the mass slides at lo and holds at hi
    for _ in range(60):
        mid = (lo + hi) / 2
        if toe_thrust(slices, math.tan(math.radians(mid)), tan_delta, cohesion) > 0:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    ap.add_argument("--delta", type=float, default=None,
                    help="interface friction angle (deg); default: the case's internal joint friction")
    ap.add_argument("--kinks-only", action="store_true", help="cut only at the breaks of the sliding surface")
    a = ap.parse_args()
    case = json.load(open(a.case))
    level = case.get("water", {}).get("level")
    default = case.get("default_joint")
    delta = a.delta if a.delta is not None else case["joints"][default]["friction_angle"]
    slices = section_slices(case, a.kinks_only)
    phi = critical_friction(slices, math.tan(math.radians(delta)))
    print(f"{len(slices)} slices, interface friction {delta:g} deg, water level {level} m: "
          f"critical friction {phi:.2f} deg")


if __name__ == "__main__":
    main()
