#!/usr/bin/env python3
"""Rigorous limit equilibrium of vertical slices: Spencer's method and Morgenstern-Price.

What: the factor of safety F of a slide mass cut into vertical slices, satisfying force AND moment
equilibrium (Spencer 1967: interslice resultants all inclined at one angle theta; Morgenstern &
Price 1965 with a half-sine interslice function), and the critical cohesion (F = 1 at a given
friction) or friction (at a given cohesion) of the sliding surface. Used on cases/chair_slide.json
as the reference the multi-wedge method of scripts/chair_slide.py (force equilibrium only, with an
assumed interface friction delta) is compared with.

Formulation: the general limit equilibrium (GLE) of Fredlund, Krahn & Pufahl (1981), as in
Fredlund & Krahn (1977, Can. Geotech. J. 14:429). The interslice shear is X = lambda f(x) E
(Spencer: f = 1, so lambda = tan(theta); Morgenstern-Price here: f = sin(pi (x - x_crown) /
(x_toe - x_crown))). Base normal N and shear S = (c L + N tan(phi)) / F act at the base midpoint;
each slice's horizontal and vertical force equilibrium is solved exactly, marching from the crown
(E = X = 0 there), for N and the interslice force E on its downslope side. For a given lambda:
  F_f(lambda): the F at which the march closes at the toe (E_toe = 0): force equilibrium;
  F_m(lambda): the F at which the moments about a point O of the weights and base forces vanish
               (the interslice forces are internal and cancel): moment equilibrium.
The solution is the lambda where F_f = F_m. It is found as the root of the moment imbalance at
force equilibrium, M(F_f(lambda), lambda): the same condition, without having to choose among the
roots of the moment equation in F, of which a point below or beside the slide can give several, or
none, near the solution. Both equilibria then hold, so F does not depend on O (checked in
scripts/test_limit_equilibrium.py, with F_m about each point meeting F_f there). Interfaces may
carry tension (standard; the multi-wedge method in vajont_limit_equilibrium.py does not allow it):
the report says where, and where the line of thrust leaves an interface. With N at the base
midpoint, a lone slice whose weight does not act over that midpoint, or slices all on one plane
without cohesion (every base reaction vertical, so no interslice force), have no solution
(ValueError).

Sign conventions: the slide moves towards +x (the crown at the left, as in the case files); the
base normal is (sin b, cos b) with b the base dip (positive down to the right); on the left face of
a slice the upslope neighbour pushes +x with E and drags it down with X, so X > 0 (theta > 0) has
the sense of a positive interface friction delta in the multi-wedge method.

Water: the reservoir is a horizontal water table, so each slice carries its effective weight
rho g A - gamma_w A_wet, acting at the combination of the two centroids (of A and of A_wet), and
the base and interslice forces are effective, with no pore pressure. That is exactly equivalent,
for forces and moments, to total weights with the hydrostatic pressures on the base, the sides and
the submerged ground surface: those pressures, integrated over the closed boundary of the wet part
of each slice, are a buoyancy gamma_w A_wet acting up through the centroid of A_wet (Archimedes),
and the hydrostatic side forces of neighbouring slices are equal and opposite.

Run: python3 scripts/spencer.py cases/chair_slide.json --friction 18 [--point X Y]
     python3 scripts/spencer.py cases/chair_slide.json --cohesion 60e3
"""
import argparse, json, math, os, sys
from collections import namedtuple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
from vajont_limit_equilibrium import value_at, slice_cuts  # noqa: E402

METHODS = ("spencer", "morgenstern-price")


class Slice(namedtuple("Slice", "x0 x1 yb0 yb1 w xw yt0 yt1")):
    """A vertical slice from x0 to x1: base from (x0, yb0) to (x1, yb1), effective weight w (N/m)
    acting at x = xw, ground (top) heights yt0, yt1 at its sides (for the line of thrust)."""
    __slots__ = ()

    @property
    def beta(self):  # base dip, positive down towards +x
        return math.atan2(self.yb0 - self.yb1, self.x1 - self.x0)

    @property
    def length(self):
        return math.hypot(self.x1 - self.x0, self.yb1 - self.yb0)

    @property
    def mid(self):
        return (self.x0 + self.x1) / 2, (self.yb0 + self.yb1) / 2


# ---------------------------------------------------------------- geometry

def _moments(x0, x1, f0, f1):
    """Integral and first moment (about x = 0) over [x0, x1] of max(0, f), f linear."""
    if f0 <= 0 and f1 <= 0:
        return 0.0, 0.0
    if f0 < 0 or f1 < 0:  # clip at the zero crossing
        xc = x0 + (x1 - x0) * f0 / (f0 - f1)
        x0, x1, f0, f1 = (xc, x1, 0.0, f1) if f0 < 0 else (x0, xc, f0, 0.0)
    dx = x1 - x0
    return dx * (f0 + f1) / 2, dx * (f0 * (2 * x0 + x1) + f1 * (x0 + 2 * x1)) / 6


def _slice_moments(ground, surface, xa, xb, level):
    """(area, x-moment) of the slice between the polylines from xa to xb, and of its part below
    the level (None: dry). Same pieces as vajont_limit_equilibrium.slice_areas."""
    xs = sorted({xa, xb} | {x for x, _ in ground + surface if xa < x < xb})
    a = ax = wa = wax = 0.0
    for x0, x1 in zip(xs, xs[1:]):
        g0, g1 = value_at(ground, x0, "right"), value_at(ground, x1, "left")
        s0, s1 = value_at(surface, x0, "right"), value_at(surface, x1, "left")
        m = _moments(x0, x1, g0 - s0, g1 - s1)
        a, ax = a + m[0], ax + m[1]
        if level is None:
            continue
        pieces = [(x0, g0, s0), (x1, g1, s1)]
        if (g0 - level) * (g1 - level) < 0:  # min(g, level) is linear on each side of the crossing
            xc = x0 + (x1 - x0) * (g0 - level) / (g0 - g1)
            pieces.insert(1, (xc, level, s0 + (s1 - s0) * (xc - x0) / (x1 - x0)))
        for (xp, gp, sp), (xq, gq, sq) in zip(pieces, pieces[1:]):
            m = _moments(xp, xq, min(gp, level) - sp, min(gq, level) - sq)
            wa, wax = wa + m[0], wax + m[1]
    return a, ax, wa, wax


def polyline_slices(ground, surface, xs, unit_weight, level=None, gamma_w=9810.0):
    """Slices between consecutive xs of the mass between the ground and the sliding surface
    (polylines, x increasing; the base of each slice is the chord of the surface between its
    sides). unit_weight rho g (N/m3); below `level` the weight is effective (see the module doc)."""
    chord = [[x, value_at(surface, x, "right" if i == 0 else "left")] for i, x in enumerate(xs)]
    out = []
    for (xa, ya), (xb, yb) in zip(chord, chord[1:]):
        a, ax, wa, wax = _slice_moments(ground, chord, xa, xb, level)
        w = unit_weight * a - gamma_w * wa
        out.append(Slice(xa, xb, ya, yb, w, (unit_weight * ax - gamma_w * wax) / w,
                         value_at(ground, xa, "right"), value_at(ground, xb, "left")))
    return out


def case_slices(case, kinks_only=False):
    """The slices of a section case, the same cuts and weights as
    vajont_limit_equilibrium.section_slices, with the positions moments need."""
    sec = case["section"]
    rho = case["materials"][sec["material"]]["density"] if "material" in sec \
        else next(iter(case["materials"].values()))["density"]
    g = -case.get("gravity", [0, -9.81])[1]
    water = case.get("water", {})
    return polyline_slices(sec["ground"], sec["sliding_surface"], slice_cuts(sec, kinks_only), rho * g,
                           water.get("level"), water.get("unit_weight", 9810.0))


# ---------------------------------------------------------------- equilibrium

def _per_slice(v, n):
    return list(v) if hasattr(v, "__len__") else [v] * n


def interslice_function(slices, method):
    """f(x) at the n + 1 slice boundaries, crown to toe."""
    xs = [s.x0 for s in slices] + [slices[-1].x1]
    if method == "spencer":
        return [1.0] * len(xs)
    if method == "morgenstern-price":
        x0, x1 = xs[0], xs[-1]
        return [math.sin(math.pi * (x - x0) / (x1 - x0)) for x in xs]
    raise ValueError(f"method {method!r}: one of {METHODS}")


def march(slices, c, tan_phi, F, lam, f):
    """Each slice's horizontal and vertical force equilibrium, from the crown (E = X = 0) to the toe.
    c, tan_phi: scalars or one per slice. Returns N, S (per slice) and E, X (per boundary, n + 1);
    E[-1] is the force the toe would need from beyond it (0 when force equilibrium holds)."""
    n = len(slices)
    cs, ts = _per_slice(c, n), _per_slice(tan_phi, n)
    E, X, N, S = [0.0], [0.0], [], []
    for i, s in enumerate(slices):
        sb, cb = math.sin(s.beta), math.cos(s.beta)
        a, b = cs[i] * s.length / F, ts[i] / F          # S = a + b N
        k = lam * f[i + 1]                              # X_right = k E_right
        # x: E_l - E_r + N sin b - S cos b = 0;  y: -X_l + X_r + N cos b + S sin b - W = 0
        p, q = sb - b * cb, cb + b * sb
        n_i = (s.w + X[-1] - k * E[-1] - a * (sb - k * cb)) / (q + k * p)
        e_r = E[-1] + n_i * p - a * cb
        N.append(n_i)
        S.append(a + b * n_i)
        E.append(e_r)
        X.append(k * e_r)
    return N, S, E, X


def moment(slices, N, S, point):
    """Moment (counter-clockwise +) about `point` of the weights and base forces."""
    ox, oy = point
    m = 0.0
    for s, n_i, s_i in zip(slices, N, S):
        sb, cb = math.sin(s.beta), math.cos(s.beta)
        dx, dy = s.mid[0] - ox, s.mid[1] - oy
        m += -s.w * (s.xw - ox) + n_i * (dx * cb - dy * sb) + s_i * (dx * sb + dy * cb)
    return m


def default_point(slices):
    """A moment point above the slide (any point gives the same solution)."""
    return ((slices[0].x0 + slices[-1].x1) / 2,
            max(max(s.yt0, s.yt1) for s in slices) + (slices[-1].x1 - slices[0].x0) / 2)


def _first_root(fn, grid, rel=1e-13):
    """A root of fn: the first sign change along grid, refined (_refine); a change across a pole
    (|fn| not small at the refined point) is skipped. None if there is none."""
    def safe(x):
        try:
            return fn(x)
        except ZeroDivisionError:  # a slice's normal-force equation is singular there
            return None

    prev_x, prev_v = None, None
    for x in grid:
        v = safe(x)
        if v is None:
            prev_x = None
            continue
        if v == 0:
            return x
        if prev_x is not None and (v > 0) != (prev_v > 0):
            root = _refine(safe, prev_x, x, prev_v, v, rel)
            fr = None if root is None else safe(root)
            if fr is not None and abs(fr) <= 1e-6 * max(abs(prev_v), abs(v)):
                return root
        prev_x, prev_v = x, v
    return None


def _refine(fn, a, b, fa, fb, rel):
    """Root of fn between a and b (fa, fb of opposite signs) by false position with the Illinois
    modification; None if fn fails inside. Keeps a bracket, so it cannot leave [a, b]."""
    side = 0
    for _ in range(200):
        x = (a * fb - b * fa) / (fb - fa)
        if not min(a, b) < x < max(a, b):
            x = (a + b) / 2
        fx = fn(x)
        if fx is None:
            return None
        if fx == 0 or abs(b - a) <= rel * max(1.0, abs(x)):
            return x
        if (fx > 0) == (fb > 0):
            b, fb = x, fx
            if side == -1:
                fa /= 2
            side = -1
        else:
            a, fa = x, fx
            if side == 1:
                fb /= 2
            side = 1
        if abs(b - a) <= rel * max(1.0, abs(x)):
            return x
    return x


F_GRID = [100 * 0.8 ** i for i in range(45)]  # 100 down to ~0.005: the first change from above


def force_fos(slices, c, tan_phi, lam, f):
    """F_f(lambda): the F that closes the march at the toe."""
    return _first_root(lambda F: march(slices, c, tan_phi, F, lam, f)[2][-1], F_GRID)


def moment_fos(slices, c, tan_phi, lam, f, point, near=None):
    """F_m(lambda): the F at which the weights and base forces have no moment about point. The
    moment can vanish at several F (or none) when the point is below or beside the slide; the root
    nearest `near` (F_f(lambda), where the two curves are to meet) is taken, searching outwards
    from it; without `near`, the first root down from F = 100."""
    def m(F):
        N, S, _, _ = march(slices, c, tan_phi, F, lam, f)
        return moment(slices, N, S, point)
    if near is None:
        return _first_root(m, F_GRID)
    grid = [near]
    for k in range(1, 40):
        grid += [near * 1.15 ** k, near / 1.15 ** k]
    return _nearest_root(m, grid)


def _nearest_root(fn, grid):
    """Like _first_root, but grid = [x0, up1, down1, up2, down2, ...] is walked outwards from x0
    on both sides at once: the root nearest x0 (on the grid's scale)."""
    def safe(x):
        try:
            return fn(x)
        except ZeroDivisionError:
            return None
    v0 = safe(grid[0])
    if v0 == 0:
        return grid[0]
    prev = {1: (grid[0], v0), -1: (grid[0], v0)}
    for x in grid[1:]:
        side = 1 if x > grid[0] else -1
        v = safe(x)
        px, pv = prev[side]
        prev[side] = (x, v)
        if v is None or pv is None:
            continue
        if v == 0:
            return x
        if (v > 0) != (pv > 0):
            root = _refine(safe, px, x, pv, v, 1e-13)
            fr = None if root is None else safe(root)
            if fr is not None and abs(fr) <= 1e-6 * max(abs(pv), abs(v)):
                return root
    return None


def lambda_grid(method):
    if method == "spencer":  # theta from -80 to 80 deg, 1 deg apart, from 0 outwards
        thetas = sorted(range(-80, 81), key=abs)
        return [math.tan(math.radians(t)) for t in thetas]
    return sorted((i / 50 for i in range(-200, 201)), key=abs)  # M-P: |lambda| <= 4


def _solve_lambda(residual, method, zero=0.0):
    """The lambda nearest 0 at which residual changes sign: the grid is walked outwards from 0 on
    both sides at once, and the first bracket found is refined. residual(lambda) may return None
    (no solution there). If |residual(0)| <= zero, 0 (e.g. residual = 0 whatever lambda: one
    slice whose weight acts over its base midpoint, where lambda is irrelevant)."""
    r0 = residual(0.0)
    if r0 is not None and abs(r0) <= zero:
        return 0.0
    prev = {1: (0.0, r0), -1: (0.0, r0)}
    for l in lambda_grid(method)[1:]:
        side = 1 if l > 0 else -1
        r = residual(l)
        prev_l, prev_r = prev[side]
        prev[side] = (l, r)
        if r is None or prev_r is None:
            continue
        if (r > 0) != (prev_r > 0):
            root = _refine(residual, prev_l, l, prev_r, r, 1e-14)
            rr = None if root is None else residual(root)
            if rr is not None and abs(rr) <= 1e-6 * max(abs(prev_r), abs(r)):
                return root  # not a jump across a pole of the residual
    return None


def _moment_scale(slices):
    """A moment (N m/m) against which an imbalance counts as zero."""
    span = slices[-1].x1 - slices[0].x0 + max(max(s.yt0, s.yt1) - min(s.yb0, s.yb1) for s in slices)
    return sum(abs(s.w) for s in slices) * span


def solve(slices, c, tan_phi, method="spencer", point=None, details=True):
    """F and lambda with force and moment equilibrium, and the interslice forces.

    lambda is found as the root of the moment imbalance about `point` at force equilibrium,
    M(F_f(lambda), lambda): that is the GLE condition F_f(lambda) = F_m(lambda) (F_f is then a root
    of the moment equation, i.e. F_m = F_f), without choosing among the roots of the moment equation
    in F, which for a moment point below or beside the slide can be several, or none, near the
    solution. With the forces closed the weights and base forces reduce to a couple, so the residual
    is the same about any point. F_m(lambda) about `point` is computed separately at the solution
    and returned ("F_m"), with F_f - F_m on either side of lambda ("gap"), to show that the two
    curves cross there.
    Returns a dict: F, lam, theta (deg, Spencer), E, X, N, S, and with details also thrust
    (thrust_line), point, F_m, gap. Raises ValueError if there is no solution."""
    point = point or default_point(slices)
    f = interslice_function(slices, method)

    def residual(lam):
        F = force_fos(slices, c, tan_phi, lam, f)
        if F is None:
            return None
        N, S, _, _ = march(slices, c, tan_phi, F, lam, f)
        return moment(slices, N, S, point)

    lam = _solve_lambda(residual, method, 1e-12 * _moment_scale(slices))
    if lam is None:
        raise ValueError(f"{method}: no lambda with both force and moment equilibrium")
    F = force_fos(slices, c, tan_phi, lam, f)
    N, S, E, X = march(slices, c, tan_phi, F, lam, f)
    result = {"F": F, "lam": lam, "theta": math.degrees(math.atan(lam)) if method == "spencer" else None,
              "E": E, "X": X, "N": N, "S": S}
    if not details:
        return result

    def gap(l):
        ff = force_fos(slices, c, tan_phi, l, f)
        fm = None if ff is None else moment_fos(slices, c, tan_phi, l, f, point, near=ff)
        return None if fm is None else ff - fm
    result.update(thrust=thrust_line(slices, E, X), point=point,
                  F_m=moment_fos(slices, c, tan_phi, lam, f, point, near=F),
                  gap=(gap(lam - 0.05), gap(lam + 0.05)))
    return result


def factor_of_safety(slices, c, tan_phi, method="spencer", point=None):
    """(F, theta in degrees) for Spencer, (F, lambda) for Morgenstern-Price (half-sine f)."""
    r = solve(slices, c, tan_phi, method, point, details=False)
    return r["F"], (r["theta"] if method == "spencer" else r["lam"])


def thrust_line(slices, E, X):
    """Height of the interslice resultant at each inner boundary, from each slice's moment
    equilibrium about its base midpoint (where N and S act), marching from the crown. The last
    slice's moment residual (about its base midpoint) is returned as the final entry: it vanishes
    when the whole mass is in moment equilibrium. None where E = 0."""
    ys, y_l = [], None
    for i, s in enumerate(slices):
        xm, ym = s.mid
        e_l, x_l, e_r, x_r = E[i], X[i], E[i + 1], X[i + 1]
        # moments about (xm, ym): weight; left face (E_l, -X_l) at (x0, y_l); right face (-E_r, X_r)
        # at (x1, y_r):  -W (xw - xm) - (x0 - xm) X_l - (y_l - ym) E_l + (x1 - xm) X_r + (y_r - ym) E_r = 0
        known = -s.w * (s.xw - xm) - (s.x0 - xm) * x_l - ((y_l - ym) * e_l if e_l else 0.0) \
            + (s.x1 - xm) * x_r
        if i == len(slices) - 1:
            ys.append(known)  # E_r = X_r = 0 at the toe: the residual
        else:
            y_l = ym - known / e_r if e_r else None
            ys.append(y_l)
    return ys


def critical_cohesion(slices, tan_phi, method="spencer", point=None):
    """(c, theta deg or lambda) with F = 1 at friction tan_phi, directly: at F = 1 and a given
    lambda the march is affine in c, so the c closing the forces, c_f(lambda), and the moment
    imbalance there follow from two marches; lambda is where that imbalance vanishes (as in solve)."""
    point = point or default_point(slices)
    f = interslice_function(slices, method)
    c_ref = 1e5

    def c_and_moment(lam):
        r0, r1 = march(slices, 0.0, tan_phi, 1.0, lam, f), march(slices, c_ref, tan_phi, 1.0, lam, f)
        e0, e1 = r0[2][-1], r1[2][-1]
        m0, m1 = moment(slices, r0[0], r0[1], point), moment(slices, r1[0], r1[1], point)
        t = e0 / (e0 - e1)
        return c_ref * t, m0 + t * (m1 - m0)

    def residual(lam):
        try:
            return c_and_moment(lam)[1]
        except ZeroDivisionError:
            return None

    lam = _solve_lambda(residual, method, 1e-12 * _moment_scale(slices))
    if lam is None:
        raise ValueError(f"{method}: no lambda with both force and moment equilibrium at F = 1")
    return c_and_moment(lam)[0], (math.degrees(math.atan(lam)) if method == "spencer" else lam)


def critical_friction(slices, cohesion, method="spencer", point=None):
    """(phi deg, theta deg or lambda) with F = 1 at the given cohesion. At c = 0, F scales with
    tan(phi) (only tan(phi) / F enters), so tan(phi_crit) = tan(phi) / F(phi) from one solve;
    otherwise bisection on phi (F rises with phi)."""
    if cohesion == 0:
        t = math.tan(math.radians(30.0))
        F, second = factor_of_safety(slices, 0.0, t, method, point)
        return math.degrees(math.atan(t / F)), second
    lo, hi = 0.0, 80.0
    for _ in range(60):
        mid = (lo + hi) / 2
        if factor_of_safety(slices, cohesion, math.tan(math.radians(mid)), method, point)[0] < 1:
            lo = mid
        else:
            hi = mid
    phi = (lo + hi) / 2
    return phi, factor_of_safety(slices, cohesion, math.tan(math.radians(phi)), method, point)[1]


# ---------------------------------------------------------------- report

def _tension(slices, E):
    """Inner boundaries (x) whose interslice normal force is tension."""
    return [s.x1 for s, e in zip(slices[:-1], E[1:-1]) if e < 0]


def _print_solution(slices, r):
    tens = _tension(slices, r["E"])
    print(f"    interfaces in tension: {', '.join(f'x {x:g}' for x in tens) if tens else 'none'}")
    fr = [None if y is None else (y - s.yb1) / (s.yt1 - s.yb1) for s, y in zip(slices[:-1], r["thrust"][:-1])]
    print("    line of thrust, height above the base / interface height: " +
          " ".join("-" if v is None else f"{v:.2f}" for v in fr))
    for s, v, e in zip(slices[:-1], fr, r["E"][1:-1]):
        if v is not None and not 0 <= v <= 1:
            print(f"      outside the interface at x {s.x1:g} (E there {e / 1e6:.3g} MN/m of "
                  f"{max(r['E']) / 1e6:.3g} at most)")


def report(case, phi=None, cohesion=None, point=None):
    import chair_slide  # multi-wedge critical cohesion, for comparison
    from vajont_limit_equilibrium import section_slices, critical_friction as wedge_friction
    slices = case_slices(case)
    wedges = section_slices(case)
    level = case.get("water", {}).get("level")
    delta_int = case["joints"][case["default_joint"]]["friction_angle"]
    print(f"{len(slices)} slices, water level {level} m, moment point {point or default_point(slices)}")
    if phi is not None:
        tan_phi = math.tan(math.radians(phi))
        print(f"sliding-surface friction {phi:g} deg: critical cohesion (F = 1)")
        thetas = []
        for method, name in (("spencer", "theta"), ("morgenstern-price", "lambda")):
            c, second = critical_cohesion(slices, tan_phi, method, point)
            r = solve(slices, c, tan_phi, method, point)
            unit = " deg" if method == "spencer" else f" (interslice inclination up to {math.degrees(math.atan(second)):.2f} deg)"
            print(f"  {method:18s} c {c / 1e3:7.2f} kPa  {name} {second:.3f}{unit}  check: F {r['F']:.9f}, "
                  f"F_m {r['F_m']:.9f}")
            _print_solution(slices, r)
            if method == "spencer":
                thetas.append(second)
        for d in sorted({0.0, 20.0, delta_int} | set(thetas)):
            c = chair_slide.critical_cohesion(wedges, tan_phi, math.tan(math.radians(d)))
            note = "  (= Spencer's theta: the same force equilibrium)" if d in thetas else ""
            print(f"  multi-wedge, interface friction {d:6.3f} deg: c {c / 1e3:7.2f} kPa{note}")
    else:
        print(f"sliding-surface cohesion {cohesion / 1e3:g} kPa: critical friction (F = 1)")
        for method, name in (("spencer", "theta"), ("morgenstern-price", "lambda")):
            p, second = critical_friction(slices, cohesion, method, point)
            unit = " deg" if method == "spencer" else ""
            print(f"  {method:18s} phi {p:6.3f} deg  {name} {second:.3f}{unit}")
        for d in sorted({0.0, 20.0, delta_int}):
            p = wedge_friction(wedges, math.tan(math.radians(d)), cohesion)
            print(f"  multi-wedge, interface friction {d:6.3f} deg: phi {p:6.3f} deg")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--friction", type=float, help="sliding-surface friction (deg): solve for cohesion")
    g.add_argument("--cohesion", type=float, help="sliding-surface cohesion (Pa): solve for friction")
    ap.add_argument("--point", type=float, nargs=2, metavar=("X", "Y"),
                    help="moment point (default: above the slide; the result does not depend on it)")
    a = ap.parse_args()
    with open(a.case) as fh:
        case = json.load(fh)
    report(case, a.friction, a.cohesion, tuple(a.point) if a.point else None)


if __name__ == "__main__":
    main()
