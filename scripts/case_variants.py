#!/usr/bin/env python3
"""Writes a case as another program or person might have written the same slope.

Metamorphic variants for the invariance checks: each changes how the slope is written,
never what it is, so `ddaslope fos` and `ddaslope critical` must give the same answer.

  scripts/case_variants.py CASE OUT.json split [--parts N]     every edge split into N (2) equal parts
  scripts/case_variants.py CASE OUT.json tjunctions            a vertex wherever another block's corner
                                                               lies on an edge (a block cutter's output)
  scripts/case_variants.py CASE OUT.json translate DX DY       the whole scene moved by (DX, DY) m
  scripts/case_variants.py CASE OUT.json mirror                reflected in x = 0 (vertices reordered)
  scripts/case_variants.py CASE OUT.json rotate DEG            scene and gravity rotated by DEG
  scripts/case_variants.py CASE OUT.json reverse-blocks        blocks listed in reverse order
  scripts/case_variants.py CASE OUT.json vertex-start K        every outline starts at its vertex K
  scripts/case_variants.py CASE OUT.json no-monitors           monitors (and expectations) removed

A case with a `section` must be cut first (`ddaslope cut CASE --out DIR` writes DIR/blocks.json).
"""
import argparse
import json
import math
import sys


def edges(poly):
    return [(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly))]


def split(case, parts):
    for b in case["blocks"]:
        out = []
        for a, c in edges(b["vertices"]):
            for k in range(parts):
                t = k / parts
                out.append([a[0] + t * (c[0] - a[0]), a[1] + t * (c[1] - a[1])])
        b["vertices"] = out


def tjunctions(case):
    """A vertex on every edge where a corner of another block lies on it (within 1e-9 of the edge)."""
    corners = [tuple(v) for b in case["blocks"] for v in b["vertices"]]
    for b in case["blocks"]:
        out = []
        for a, c in edges(b["vertices"]):
            out.append(a)
            dx, dy = c[0] - a[0], c[1] - a[1]
            length2 = dx * dx + dy * dy
            inner = []
            for p in corners:
                t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2
                if not 1e-9 < t < 1 - 1e-9:
                    continue
                off = abs((p[0] - a[0]) * dy - (p[1] - a[1]) * dx) / math.sqrt(length2)
                if off <= 1e-9 * math.sqrt(length2):
                    inner.append((t, [a[0] + t * dx, a[1] + t * dy]))
            inner.sort()
            last = None
            for t, q in inner:
                if last is None or t - last > 1e-9:
                    out.append(q)
                    last = t
        b["vertices"] = out


def transform_points(case, f):
    for b in case["blocks"]:
        b["vertices"] = [f(v) for v in b["vertices"]]
    for key in ("monitors", "point_loads", "fixed_points"):
        for m in case.get(key, []):
            m["point"] = f(m["point"])
    for s in case.get("supports", []):  # a bolt or anchor: its head and end are points of the scene
        s["head"] = f(s["head"])
        s["end"] = f(s["end"])
    for load in case.get("edge_loads", []):  # a loaded stretch of a face: its two ends
        load["from"] = f(load["from"])
        load["to"] = f(load["to"])
    water = case.get("water", {})
    if "phreatic_line" in water:
        water["phreatic_line"] = [f(p) for p in water["phreatic_line"]]
    grid = water.get("pressure_grid", {})
    if "points" in grid:  # [x, y, p]: the point moves, its pressure stays
        grid["points"] = [f(p[:2]) + [p[2]] for p in grid["points"]]
    elif "csv" in grid:
        sys.exit("a pressure grid read from a CSV file: write its points into the case first")


def rotate_vector(v, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [c * v[0] - s * v[1], s * v[0] + c * v[1]]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("variant", choices=["split", "tjunctions", "translate", "mirror", "rotate", "reverse-blocks",
                                        "vertex-start", "no-monitors"])
    ap.add_argument("values", nargs="*", type=float)
    ap.add_argument("--parts", type=int, default=2)
    a = ap.parse_args()
    with open(a.case) as f:
        case = json.load(f)
    if "section" in case:
        sys.exit(f"{a.case}: has a section; cut it first (ddaslope cut {a.case} --out DIR) and vary DIR/blocks.json")
    v = a.variant
    if v == "split":
        split(case, a.parts)
    elif v == "tjunctions":
        tjunctions(case)
    elif v == "translate":
        dx, dy = a.values
        transform_points(case, lambda p: [p[0] + dx, p[1] + dy])
        if "level" in case.get("water", {}):
            case["water"]["level"] += dy  # a level is an elevation: it moves with the scene
    elif v == "mirror":
        transform_points(case, lambda p: [-p[0], p[1]])
        for b in case["blocks"]:
            b["vertices"].reverse()
        if "phreatic_line" in case.get("water", {}):
            case["water"]["phreatic_line"].reverse()  # x increasing again
        case["gravity"] = [-case.get("gravity", [0, -9.81])[0], case.get("gravity", [0, -9.81])[1]]
        if "seismic" in case and "k_h" in case["seismic"]:
            case["seismic"]["k_h"] = -case["seismic"]["k_h"]
        if "record" in case.get("seismic", {}):  # the ground shakes the mirrored way
            record = case["seismic"]["record"]
            if record.get("vertical_column"):
                sys.exit("mirror: a record with a vertical column; its scale would flip both components")
            record["scale"] = -record.get("scale", 1.0)
        for b in case["blocks"]:
            if "velocity" in b:
                b["velocity"][0] = -b["velocity"][0]
        for load in case.get("point_loads", []):
            load["force"][0] = -load["force"][0]
            if "rate" in load:
                load["rate"][0] = -load["rate"][0]
        for load in case.get("edge_loads", []):
            if "load" in load:  # a traction [qx, qy], or one at each end
                q = load["load"]
                load["load"] = [[-t[0], t[1]] for t in q] if isinstance(q[0], list) else [-q[0], q[1]]
    elif v == "rotate":
        (deg,) = a.values
        transform_points(case, lambda p: rotate_vector(p, deg))
        case["gravity"] = rotate_vector(case.get("gravity", [0, -9.81]), deg)
        for load in case.get("point_loads", []):
            load["force"] = rotate_vector(load["force"], deg)
            if "rate" in load:
                load["rate"] = rotate_vector(load["rate"], deg)
        for load in case.get("edge_loads", []):
            if "load" in load:
                q = load["load"]
                load["load"] = [rotate_vector(t, deg) for t in q] if isinstance(q[0], list) else rotate_vector(q, deg)
        if "water" in case:
            sys.exit("rotate: a water table is horizontal by definition; rotate a case without water")
    elif v == "reverse-blocks":
        case["blocks"].reverse()
    elif v == "vertex-start":
        (k,) = a.values
        for b in case["blocks"]:
            n = len(b["vertices"])
            s = int(k) % n
            b["vertices"] = b["vertices"][s:] + b["vertices"][:s]
    elif v == "no-monitors":
        case.pop("monitors", None)
        case.pop("expected", None)
    with open(a.out, "w") as f:
        json.dump(case, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
