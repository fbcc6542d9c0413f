#!/usr/bin/env python3
"""Why a deformable DDA block can walk down a slope: the flutter of steady sliding.

Linearises Shi's constant-strain block (six unknowns: u0, v0, r0, εx, εy, γxy about the centroid)
sliding on a rigid plane on its two base corners, each a normal penalty spring p, with Coulomb
friction, and prints the growth rate (1/s) of its fastest mode:
  per end: each corner's friction is μ N_i (original DDA, and ddaslope before issue #17's fix);
  shared:  the edge's friction μ (N1 + N2) is shared equally by its ends (ddaslope's edge rule).
Per-end friction makes the stiffness non-symmetric: μ p T_x(i)ᵀ T_y(i) couples the normal
motion of each corner into shear along the edge; the stretch it drives returns as a normal
squeeze through Poisson's ratio, and two modes coalesce into one that grows. Shared friction
depends on the sum of the normal forces only and the loop is cut (no growth anywhere below).

usage: friction_flutter.py [--young 5e9] [--poisson 0.25] [--density 2000] [--penalty-factor 40]
                           [--size 10x10] [--phi 39.9]     one scene, both rules
       friction_flutter.py --scan                          the worst growth over a grid of scenes
Needs numpy (python3-numpy).
"""
import argparse
import itertools

import numpy as np


def t_matrix(x, y):
    """Shi's displacement matrix T at (x, y) about the centroid."""
    return np.array([[1, 0, -y, x, 0, y / 2], [0, 1, x, 0, y, x / 2]], float)


def matrices(young, nu, rho, p, mu, width, height, shared):
    a, b = width / 2, height / 2
    g, w = np.polynomial.legendre.leggauss(3)  # exact for the quadratic integrand of ∫TᵀT
    mass = sum(rho * wi * wj * a * b * t_matrix(a * xi, b * yj).T @ t_matrix(a * xi, b * yj)
               for xi, wi in zip(g, w) for yj, wj in zip(g, w))
    e, n = young / (1 - nu ** 2), nu / (1 - nu)  # plane strain
    d = e / (1 - n * n) * np.array([[1, n, 0], [n, 1, 0], [0, 0, (1 - n) / 2]])
    k = np.zeros((6, 6))
    k[3:, 3:] = width * height * d
    corners = [t_matrix(x, -b) for x in (-a, a)]
    for t in corners:
        k += p * np.outer(t[1], t[1])  # normal springs
    total_normal = sum(t[1] for t in corners)
    for t in corners:  # friction −μ N along x on a block sliding in +x, N = −p T_y d
        k -= mu * p * np.outer(t[0], total_normal / 2 if shared else t[1])
    return mass, k


def growth(mass, k):
    a = np.zeros((12, 12))
    a[:6, 6:] = np.eye(6)
    a[6:, :6] = -np.linalg.solve(mass, k)
    rate = max(np.linalg.eigvals(a).real)
    return rate if rate > 1e-6 else 0.0  # below: round-off of the eigensolver


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--young", type=float, default=5e9)
    ap.add_argument("--poisson", type=float, default=0.25)
    ap.add_argument("--density", type=float, default=2000)
    ap.add_argument("--penalty-factor", type=float, default=40)
    ap.add_argument("--size", default="10x10", help="width x height (m)")
    ap.add_argument("--phi", type=float, default=39.9)
    ap.add_argument("--scan", action="store_true")
    o = ap.parse_args()
    if not o.scan:
        w, h = (float(s) for s in o.size.split("x"))
        mu = np.tan(np.radians(o.phi))
        for shared in (False, True):
            m, k = matrices(o.young, o.poisson, o.density, o.penalty_factor * o.young, mu, w, h, shared)
            print(f"{'shared' if shared else 'per end':8s} growth {growth(m, k):8.2f} 1/s")
        return
    worst = {False: (0, None), True: (0, None)}
    grid = itertools.product([5e8, 5e9, 5e10], [0.0, 0.1, 0.25, 0.4, 0.49], [1, 10, 40, 100],
                             [5, 20, 40, 60, 75], [(10, 10), (20, 5), (5, 20), (10, 1), (1, 10)])
    count = 0
    for young, nu, pf, phi, (w, h) in grid:
        count += 1
        for shared in (False, True):
            m, k = matrices(young, nu, 2000, pf * young, np.tan(np.radians(phi)), w, h, shared)
            g = growth(m, k)
            if g > worst[shared][0]:
                worst[shared] = (g, f"E {young:.0e}, ν {nu}, p {pf} E, φ {phi}°, {w:g} x {h:g} m")
    print(f"{count} scenes (E 5e8-5e10, ν 0-0.49, p 1-100 E, φ 5-75°, five block shapes)")
    for shared in (False, True):
        g, where = worst[shared]
        print(f"{'shared' if shared else 'per end':8s} worst growth {g:9.3g} 1/s" + (f" ({where})" if where else " (every scene stable)"))


if __name__ == "__main__":
    main()
