#!/usr/bin/env python3
"""Limit equilibrium of the blocks themselves: the least strength for which the cut blocks can stand.

What: reads the blocks of a case (a block case, or a section case cut first by `ddaslope cut`),
finds where they touch (edge against edge over a length; vertex against edge at a point) and finds,
by linear programming, the least cohesion (or friction angle, by bisection on the LP's feasibility)
of one joint for which a set of contact forces exists that holds every free block in force and
moment equilibrium under its weight and the water, with Mohr-Coulomb at every contact:
  - an edge-to-edge interface carries a normal and a shear force at each of its two ends (any
    pressure distribution along it is one such pair), each end |S| <= N tan(phi) + c L/2 and
    N >= -sigma_t L/2 (Livesley 1978's rigid-block formulation);
  - a vertex touching an edge (including a vertex in a concave corner of the other block, which
    touches both of its edges) carries N >= 0, |S| <= N tan(phi), no cohesion or tension;
  - water: hydrostatic pressure on every edge below the water line, as ddaslope applies it
    (docs/case-format.md), whose resultant on a block is the buoyancy of its submerged part.

Limits: each end of an interface obeys Mohr-Coulomb on its own (c L/2, sigma_t L/2), where DDA's
default edge rule judges the pair as a whole, so with a tensile strength above c/tan(phi) the two
can differ; a vertex in another block's concave corner may push on both of its edges; the forces
printed are those of one optimal set, not unique. The bound is that of the blocks as drawn: blocks
that rearrange (a thin block squeezed out) are other blocks.

Why: these are DDA's own blocks, contacts and contact laws. A block model at rest IS such a
force set, so no DDA run of these blocks can stand below this cohesion (the static theorem; with
non-associated friction it is the lower end for the real mechanism). Slice methods (Spencer,
Morgenstern-Price) assume interslice forces and let each slice's base carry all of its reaction;
they cannot put a reaction at a corner, which is what rigid blocks do at a concave kink of a sliding
surface (docs/calibration.md). The comparison separates what the blocks are from what DDA
computes with them.

Run: python3 scripts/block_equilibrium.py CASE --joint sliding_surface --friction 18 [--json]
          [--kh K] [--kv K]                 (pseudo-static coefficients instead of the case's)
          [--without-corners [BLOCK ...]]   (no corner forces: of those blocks, or of any)
          [--kink-block-width M]            (a section case cut with another kink block width)
     python3 scripts/block_equilibrium.py CASE --joint sliding_surface --cohesion 50e3 --solve friction
     python3 scripts/block_equilibrium.py CASE --solve fos
          (the strength-reduction F: every joint's c and tan(phi) divided by F, as `ddaslope fos` does)
     python3 scripts/block_equilibrium.py CASE --solve seismic-coefficient --direction=-x
          (the largest horizontal coefficient the blocks stand: the yield acceleration k_y)
     (CASE with a "section": the script calls build/ddaslope cut; --ddaslope PATH to point elsewhere)
Needs scipy (Debian python3-scipy, installed by scripts/install-deps).
"""
import argparse, json, math, os, subprocess, sys, tempfile

try:
    import numpy as np
    from scipy.optimize import linprog
except ImportError:
    sys.exit("block_equilibrium: needs numpy and scipy (Debian: apt install python3-scipy, as scripts/install-deps "
             "does; run it with /usr/bin/python3 if another python3 comes first on PATH)")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WATER_UNIT_WEIGHT = 9810.0


def load_blocks(case_path, ddaslope, kink_block_width=None):
    """The case as a block case (dict): section cases are cut by ddaslope first, with another
    section.kink_block_width if given."""
    with open(case_path) as f:
        case = json.load(f)
    if "blocks" in case:
        return case
    with tempfile.TemporaryDirectory() as tmp:
        if kink_block_width is not None:
            case["section"]["kink_block_width"] = kink_block_width
            case_path = os.path.join(tmp, "case.json")
            with open(case_path, "w") as f:
                json.dump(case, f)
        subprocess.run([ddaslope, "cut", case_path, "--out", tmp], check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(tmp, "blocks.json")) as f:
            return json.load(f)


def area_centroid(poly):
    """Signed area and centroid of a polygon (counter-clockwise > 0)."""
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        cr = x0 * y1 - x1 * y0
        a += cr
        cx += (x0 + x1) * cr
        cy += (y0 + y1) * cr
    a *= 0.5
    return a, (cx / (6 * a), cy / (6 * a)) if a != 0 else (0.0, 0.0)


def below(poly, level):
    """The part of a convex or concave polygon below y = level (Sutherland-Hodgman on one line)."""
    out = []
    for p, q in zip(poly, poly[1:] + poly[:1]):
        pin, qin = p[1] <= level, q[1] <= level
        if pin:
            out.append(p)
        if pin != qin:
            t = (level - p[1]) / (q[1] - p[1])
            out.append((p[0] + t * (q[0] - p[0]), level))
    return out


def edges(poly):
    return list(zip(poly, poly[1:] + poly[:1]))


def contacts_between(pa, pb, tol):
    """Interfaces (edge against edge: two end points, normal into a) and point contacts (a vertex of
    one on an edge of the other) of two polygons. Normals are unit vectors pointing into the block
    that the force acts on; each contact is (block-side 'a' or 'b', point, normal, length or 0)."""
    found = []
    ends = set()
    for (p0, p1) in edges(pa):
        ea = np.subtract(p1, p0); la = np.linalg.norm(ea); ta = ea / la
        for (q0, q1) in edges(pb):
            eb = np.subtract(q1, q0); lb = np.linalg.norm(eb)
            if abs(np.cross(ta, eb / lb)) > 1e-6 or np.dot(ta, eb) > 0:
                continue  # not antiparallel (to 1e-6 rad: cut blocks' edges are exact)
            na = np.array([-ta[1], ta[0]])  # inward normal of a (counter-clockwise polygons)
            if abs(np.dot(np.subtract(q0, p0), na)) > tol:
                continue  # not on one line
            lo, hi = max(0.0, min(np.dot(np.subtract(q0, p0), ta), np.dot(np.subtract(q1, p0), ta))), \
                min(la, max(np.dot(np.subtract(q0, p0), ta), np.dot(np.subtract(q1, p0), ta)))
            if hi - lo <= tol:
                continue
            a_end, b_end = np.add(p0, lo * ta), np.add(p0, hi * ta)
            found.append(("a", tuple(a_end), tuple(na), hi - lo))
            found.append(("a", tuple(b_end), tuple(na), hi - lo))
            ends.update({("a", _key(a_end), _key(na)), ("a", _key(b_end), _key(na))})
    for side, poly, other in (("a", pa, pb), ("b", pb, pa)):
        for k, v in enumerate(poly):
            sides = [np.subtract(poly[k - 1], v), np.subtract(poly[(k + 1) % len(poly)], v)]
            sides = [d / np.linalg.norm(d) for d in sides]
            for (q0, q1) in edges(other):
                e = np.subtract(q1, q0); l = np.linalg.norm(e); t = e / l
                n_out = np.array([t[1], -t[0]])  # outward normal of the other block's edge
                r = np.dot(np.subtract(v, q0), t)
                if r < -tol or r > l + tol or abs(np.dot(np.subtract(v, q0), n_out)) > tol:
                    continue
                # Only a corner that lies wholly outside the edge's line can press on it: a vertex
                # beside the edge's end (two blocks' corners meeting on a joint) cannot.
                if any(np.dot(d, n_out) < -1e-9 for d in sides):
                    continue
                # the force on the vertex's block pushes it out of the other block
                normal = tuple(n_out)
                key = ("a", _key(v), _key(n_out)) if side == "a" else ("a", _key(v), _key(-n_out))
                if key in ends:
                    continue  # already an end of an edge-to-edge interface with this normal
                found.append((side, tuple(v), normal, 0.0))
    return found


def _key(p):
    return (round(float(p[0]), 6), round(float(p[1]), 6))


class BlockModel:
    """The blocks' equilibrium equations and Mohr-Coulomb constraints for linprog."""

    def __init__(self, case):
        self.case = case
        self.blocks = case["blocks"]
        for b in self.blocks:  # counter-clockwise, as ddaslope stores them
            if area_centroid([tuple(v) for v in b["vertices"]])[0] < 0:
                b["vertices"] = list(reversed(b["vertices"]))
        names = [b.get("id", str(i)) for i, b in enumerate(self.blocks)]
        self.index = {n: i for i, n in enumerate(names)}
        joints = case["joints"]
        self.joints = joints
        # As the case reader: a single joint is every pair's without default_joint.
        default = case.get("default_joint", next(iter(joints)) if len(joints) == 1 else None)
        self.pair_joint = {}
        for jp in case.get("joint_pairs", []):
            a, b = (self.index[n] for n in jp["blocks"])
            self.pair_joint[(min(a, b), max(a, b))] = jp["joint"]
        self.default_joint = default
        xs = [v[0] for b in self.blocks for v in b["vertices"]]
        ys = [v[1] for b in self.blocks for v in b["vertices"]]
        tol = 1e-7 * max(max(xs) - min(xs), max(ys) - min(ys))  # of the model's size, not its coordinates
        self.contacts = []  # (block on which N n + S t acts, other block, point, n, length, joint)
        polys = [[tuple(v) for v in b["vertices"]] for b in self.blocks]
        for i in range(len(polys)):
            for j in range(i + 1, len(polys)):
                if self.blocks[i].get("fixed") and self.blocks[j].get("fixed"):
                    continue
                if not _boxes_touch(polys[i], polys[j], tol):
                    continue
                joint = self.pair_joint.get((i, j), default)
                for side, p, n, length in contacts_between(polys[i], polys[j], tol):
                    on, other = (i, j) if side == "a" else (j, i)
                    self.contacts.append((on, other, p, n, length, joint))
        self.polys = polys
        self.gravity = case.get("gravity", [0, -9.81])
        self.densities = {k: v["density"] for k, v in case["materials"].items()}
        self.level = case.get("water", {}).get("level")
        if "water" in case and self.level is None:
            sys.exit("block_equilibrium: only a reservoir level (water.level) is supported")
        self.gamma_w = case.get("water", {}).get("unit_weight", WATER_UNIT_WEIGHT)
        # Pseudo-static seismic coefficients (docs/seismic.md): a force (k_h, k_v)·m·|g|, +x and up.
        seismic = case.get("seismic", {})
        self.kh, self.kv = seismic.get("k_h", 0.0), seismic.get("k_v", 0.0)

    def loads(self, b):
        """Weight and buoyancy of block b: force (fx, fy) and its moment about the origin."""
        poly = self.polys[b]
        area, (cx, cy) = area_centroid(poly)
        rho = self.densities[self.blocks[b]["material"]]
        # k_h along the horizontal (+x turned perpendicular to gravity), k_v up (as ddaslope).
        g = math.hypot(*self.gravity)
        up = (-self.gravity[0] / g, -self.gravity[1] / g)
        horizontal = (up[1], -up[0])
        fx = rho * area * (self.gravity[0] + g * (self.kh * horizontal[0] + self.kv * up[0]))
        fy = rho * area * (self.gravity[1] + g * (self.kh * horizontal[1] + self.kv * up[1]))
        m = cx * fy - cy * fx
        if self.level is not None:
            sub = below(poly, self.level)
            if len(sub) >= 3:
                a_s, (sx, sy) = area_centroid(sub)
                up = self.gamma_w * a_s
                fy += up
                m += sx * up
        return fx, fy, m

    def feasible_or_min(self, joint, phi_of, c_of, minimise_c):
        """Builds and solves the LP. phi_of/c_of: joint name -> value (the searched joint's c is the
        LP's last variable when minimise_c). Returns the least c (minimise_c) or feasibility."""
        free = [b for b in range(len(self.blocks)) if not self.blocks[b].get("fixed")]
        row = {b: k for k, b in enumerate(free)}
        nv = 2 * len(self.contacts) + (1 if minimise_c else 0)
        a_eq = np.zeros((3 * len(free), nv))
        b_eq = np.zeros(3 * len(free))
        for b in free:
            fx, fy, m = self.loads(b)
            b_eq[3 * row[b]:3 * row[b] + 3] = (-fx, -fy, -m)
        a_ub, b_ub, bounds = [], [], []
        for k, (on, other, p, n, length, jname) in enumerate(self.contacts):
            n = np.array(n); t = np.array([-n[1], n[0]])
            for blk, sign in ((on, 1.0), (other, -1.0)):
                if blk not in row:
                    continue
                r = 3 * row[blk]
                for col, d in ((2 * k, n), (2 * k + 1, t)):
                    a_eq[r, col] += sign * d[0]
                    a_eq[r + 1, col] += sign * d[1]
                    a_eq[r + 2, col] += sign * (p[0] * d[1] - p[1] * d[0])
            tan_phi = math.tan(math.radians(phi_of(jname)))
            half = length / 2
            sigma_t = self.joints[jname].get("tensile_strength", 0.0) if length > 0 else 0.0
            bounds += [(-sigma_t * half, None), (None, None)]
            for s in (1.0, -1.0):  # s S - N tan(phi) - c L/2 <= 0
                rowv = np.zeros(nv)
                rowv[2 * k + 1], rowv[2 * k] = s, -tan_phi
                rhs = 0.0
                if jname == joint and minimise_c:
                    rowv[-1] = -half
                else:
                    rhs = c_of(jname) * half
                a_ub.append(rowv)
                b_ub.append(rhs)
        if minimise_c:
            bounds.append((0, None))
        cost = np.zeros(nv)
        if minimise_c:
            cost[-1] = 1.0
        res = linprog(cost, A_ub=np.array(a_ub), b_ub=np.array(b_ub), A_eq=a_eq, b_eq=b_eq,
                      bounds=bounds, method="highs")
        if minimise_c:
            if res.status == 2:
                return math.inf
            if res.status != 0:
                sys.exit(f"block_equilibrium: the LP did not solve ({res.message})")
            self.corner_forces = [(self.blocks[on].get("id", str(on)), p, math.hypot(res.x[2 * k], res.x[2 * k + 1]))
                                  for k, (on, _, p, _, length, _) in enumerate(self.contacts) if length == 0]
            return res.x[-1]
        return res.status == 0


def _boxes_touch(pa, pb, tol):
    ax, ay = zip(*pa); bx, by = zip(*pb)
    return not (max(ax) < min(bx) - tol or max(bx) < min(ax) - tol or
                max(ay) < min(by) - tol or max(by) < min(ay) - tol)


def critical_cohesion(model, joint, friction):
    phi = lambda j: friction if j == joint else model.joints[j]["friction_angle"]
    c = lambda j: model.joints[j].get("cohesion", 0.0)
    return model.feasible_or_min(joint, phi, c, True)


def critical_friction(model, joint, cohesion, width=1e-3):
    c = lambda j: cohesion if j == joint else model.joints[j].get("cohesion", 0.0)
    def holds(f):
        phi = lambda j: f if j == joint else model.joints[j]["friction_angle"]
        return model.feasible_or_min(joint, phi, c, False)
    lo, hi = 0.0, 89.9
    if holds(lo):
        return 0.0
    if not holds(hi):
        return math.inf
    while hi - lo > width:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if holds(mid) else (mid, hi)
    return hi


def strength_reduction_factor(model, width=1e-6):
    """The F of strength reduction (`ddaslope fos`) for these blocks: the largest F for which
    c/F and atan(tan(phi)/F) on every joint still hold them (inf: beyond 100; 0: not even at 0.01)."""
    def holds(f):
        phi = lambda j: math.degrees(math.atan(math.tan(math.radians(model.joints[j]["friction_angle"])) / f))
        c = lambda j: model.joints[j].get("cohesion", 0.0) / f
        return model.feasible_or_min(None, phi, c, False)
    lo, hi = 0.01, 100.0
    if not holds(lo):
        return 0.0
    if holds(hi):
        return math.inf
    while hi - lo > width * lo:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if holds(mid) else (lo, mid)
    return 0.5 * (lo + hi)


def yield_coefficient(model, direction, width=1e-6):
    """The largest horizontal coefficient along `direction` (+1: +x) the blocks can stand, with
    their strengths: the yield acceleration k_y in g (inf: beyond 2; -1: not even at 0)."""
    c = lambda j: model.joints[j].get("cohesion", 0.0)
    phi = lambda j: model.joints[j]["friction_angle"]
    def holds(k):
        model.kh = direction * k
        return model.feasible_or_min(None, phi, c, False)
    lo, hi = 0.0, 2.0
    if not holds(lo):
        return -1.0
    if holds(hi):
        return math.inf
    while hi - lo > width:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if holds(mid) else (lo, mid)
    return 0.5 * (lo + hi)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    ap.add_argument("--joint", help="the joint to solve for (cohesion, friction)")
    ap.add_argument("--solve", choices=["cohesion", "friction", "seismic-coefficient", "fos"], default="cohesion",
                    help="fos: the strength-reduction factor, every joint's c and tan(phi) divided by F")
    ap.add_argument("--direction", choices=["+x", "-x"], default="+x",
                    help="seismic-coefficient: the direction of the horizontal load")
    ap.add_argument("--kh", type=float, help="horizontal seismic coefficient (+x), instead of the case's")
    ap.add_argument("--kv", type=float, help="vertical seismic coefficient (up), instead of the case's")
    ap.add_argument("--friction", type=float, help="friction angle of the joint (deg) when solving c")
    ap.add_argument("--cohesion", type=float, help="cohesion of the joint (Pa) when solving phi")
    ap.add_argument("--ddaslope", default=os.path.join(ROOT, "build", "ddaslope"))
    ap.add_argument("--without-corners", nargs="*", metavar="BLOCK",
                    help="leave out the vertex-to-edge contacts (of the named blocks, or all): what slices assume")
    ap.add_argument("--kink-block-width", type=float, metavar="M",
                    help="cut the section with this section.kink_block_width instead of the case's (0: none)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    model = BlockModel(load_blocks(args.case, args.ddaslope, args.kink_block_width))
    if args.kh is not None:
        model.kh = args.kh
    if args.kv is not None:
        model.kv = args.kv
    if args.without_corners is not None:
        named = set(args.without_corners)
        model.contacts = [c for c in model.contacts
                          if c[4] > 0 or (named and model.blocks[c[0]].get("id") not in named)]
    if args.solve == "seismic-coefficient":
        k = yield_coefficient(model, 1 if args.direction == "+x" else -1)
        if k < 0:
            sys.exit(f"block_equilibrium: {args.case}: the blocks cannot stand without seismic loading")
        text = "beyond 2" if math.isinf(k) else f"{k:.6g}"
        if args.json:
            print(json.dumps({"solve": args.solve, "direction": args.direction, "value": None if math.isinf(k) else k,
                              "unit": "g", "blocks": len(model.blocks), "contact_points": len(model.contacts)}))
        else:
            print(f"{args.case}: largest horizontal seismic coefficient along {args.direction} the blocks can stand "
                  f"(k_v = {model.kv:g}): {text} g ({len(model.blocks)} blocks, {len(model.contacts)} contact points)")
        return
    if args.solve == "fos":
        f = strength_reduction_factor(model)
        if args.json:
            print(json.dumps({"solve": "fos", "value": None if math.isinf(f) else f, "blocks": len(model.blocks),
                              "contact_points": len(model.contacts)}))
        else:
            text = "beyond 100" if math.isinf(f) else f"{f:.6g}"
            print(f"{args.case}: largest strength-reduction factor F at which the blocks can stand: {text} "
                  f"({len(model.blocks)} blocks, {len(model.contacts)} contact points)")
        return
    if args.joint is None:
        sys.exit("block_equilibrium: --joint is needed to solve for cohesion or friction")
    if args.joint not in model.joints:
        sys.exit(f"block_equilibrium: {args.case}: no joint named '{args.joint}'")
    point = sum(1 for c in model.contacts if c[4] == 0)
    model.corner_forces = []
    if args.solve == "cohesion":
        if args.friction is None:
            sys.exit("block_equilibrium: --friction is needed to solve for cohesion")
        value, unit = critical_cohesion(model, args.joint, args.friction), "Pa"
    else:
        if args.cohesion is None:
            sys.exit("block_equilibrium: --cohesion is needed to solve for friction")
        value, unit = critical_friction(model, args.joint, args.cohesion), "deg"
    if math.isinf(value):
        sys.exit(f"block_equilibrium: {args.case}: no contact forces hold these blocks at any {args.solve} "
                 "(a block resting on a corner alone, with its corners left out?)")
    corners = [{"block": b, "point": list(p), "force_N_per_m": f} for b, p, f in model.corner_forces]
    if args.json:
        print(json.dumps({"solve": args.solve, "value": value, "unit": unit,
                          "blocks": len(model.blocks), "contact_points": len(model.contacts),
                          "point_contacts": point, "corner_forces": corners}))
    else:
        print(f"{args.case}: least {args.solve} of '{args.joint}' for which the blocks can stand: "
              f"{value:.6g} {unit} ({len(model.blocks)} blocks, {len(model.contacts)} contact points, "
              f"{point} of them vertex-to-edge)")
        for c in sorted(corners, key=lambda c: -c["force_N_per_m"]):
            if c["force_N_per_m"] > 0:
                print(f"  corner of {c['block']} at ({c['point'][0]:.6g}, {c['point'][1]:.6g}) carries "
                      f"{c['force_N_per_m'] / 1e6:.3g} MN/m in one such force set")


if __name__ == "__main__":
    main()
