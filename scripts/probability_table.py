#!/usr/bin/env python3
"""The planar-failure probability table of docs/probability.md (issue #18).

Runs `ddaslope probability` on calibration/planar_failure/probability.json (c normal 20 +- 5 kPa,
phi normal 30 +- 3 deg, correlation -0.5) with both measures and both samplings, and prints a
Markdown table beside the exact values of the closed form, Hoek & Bray's
FS = (c A + W cos psi tan phi)/(W sin psi), integrated here (Simpson, standard library only).

    python3 scripts/probability_table.py [--cli build/ddaslope] [--out out/probability_table]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
JOB = os.path.join(ROOT, "calibration", "planar_failure", "probability.json")
CASE = os.path.join(ROOT, "cases", "planar_failure.json")


def geometry():
    """W (N/m), A (m) and psi (rad) of the case's wedge."""
    case = json.load(open(CASE))
    wedge = next(b for b in case["blocks"] if b["id"] == "wedge")
    v = wedge["vertices"]
    area = 0.5 * abs(sum(v[k][0] * v[(k + 1) % len(v)][1] - v[(k + 1) % len(v)][0] * v[k][1] for k in range(len(v))))
    density = case["materials"][wedge["material"]]["density"]
    g = math.hypot(*case["gravity"])
    return area * density * g, math.hypot(v[1][0] - v[0][0], v[1][1] - v[0][1]), math.atan2(v[1][1] - v[0][1], v[1][0] - v[0][0])


def phi_cdf(x):
    return 0.5 * math.erfc(-x / math.sqrt(2))


def simpson(f, a, b, n=4000):
    h = (b - a) / n
    return h / 3 * sum(f(a + k * h) * (1 if k in (0, n) else 4 if k % 2 else 2) for k in range(n + 1))


def exact(mc, sc, mp, sp, rho):
    """Pf = P(FS < 1), and the mean and sd of FS, for (c, phi) binormal."""
    W, A, psi = geometry()
    pdf = lambda z: math.exp(-0.5 * z * z) / math.sqrt(2 * math.pi)
    tan = lambda z: math.tan(math.radians(mp + sp * z))

    def fails(z2):
        ccrit = W * (math.sin(psi) - math.cos(psi) * tan(z2)) / A
        return pdf(z2) * phi_cdf(((ccrit - mc) / sc - rho * z2) / math.sqrt(1 - rho * rho))

    # |z2| <= 8: phi stays in (6, 54) degrees; the tails beyond hold 1e-15.
    pf = simpson(fails, -8, 8)
    et = simpson(lambda z: pdf(z) * tan(z), -8, 8)
    vt = simpson(lambda z: pdf(z) * (tan(z) - et) ** 2, -8, 8)
    cov = rho * sc * simpson(lambda z: pdf(z) * z * tan(z), -8, 8)  # Cov(c, tan phi)
    k = W * math.cos(psi)
    mean = (A * mc + k * et) / (W * math.sin(psi))
    sd = math.sqrt(A * A * sc * sc + k * k * vt + 2 * A * k * cov) / (W * math.sin(psi))
    return pf, mean, sd


def run(cli, out, args):
    start = time.time()
    subprocess.run([cli, "probability", JOB, "--out", out, "--overwrite"] + args, check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - start
    return json.load(open(os.path.join(out, "summary.json"))), wall


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cli", default=os.path.join(ROOT, "build", "ddaslope"))
    p.add_argument("--out", default="out/probability_table")
    a = p.parse_args()
    section = json.load(open(JOB))["probability"]
    c, phi = (i for i in section["inputs"])
    rho = section["correlations"][0]["rho"]
    pf, mean, sd = exact(c["mean"], c["sd"], phi["mean"], phi["sd"], rho)
    beta = -normal_quantile(pf)
    print(f"exact (closed form): Pf = {pf:.5f}, beta = {beta:.4f}, F mean {mean:.4f}, sd {sd:.4f}, "
          f"(mean F - 1)/sd F = {(mean - 1) / sd:.4f}\n")
    print("| measure | sampling | N | Pf | 95 % interval (Wilson) | exact inside | β | F: mean, sd | (F̄ − 1)/s_F | wall |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for measure, sampling, n, seed in [("verdict", "latin_hypercube", 400, 1), ("verdict", "monte_carlo", 400, 1),
                                       ("verdict", "latin_hypercube", 400, 2), ("verdict", "latin_hypercube", 2000, 1),
                                       ("fos", "latin_hypercube", 100, 1), ("fos", "monte_carlo", 100, 1)]:
        out = os.path.join(a.out, f"{measure}_{sampling}_{n}_{seed}")
        s, wall = run(a.cli, out, ["--measure", measure, "--sampling", sampling, "--samples", str(n), "--seed", str(seed)])
        lo, hi = s["interval_95"]
        f = s.get("factor_of_safety")
        fcol = f"{f['mean']:.4f}, {f['sd']:.4f}" if f else ""
        bcol = f"{f['reliability_index_moments']:.3f}" if f else ""
        print(f"| {measure} | {sampling} (seed {seed}) | {n} | {s['probability_of_failure']:.4f} | {lo:.4f}–{hi:.4f} | "
              f"{'yes' if lo <= pf <= hi else 'NO'} | {s['reliability_index']:.3f} | {fcol} | {bcol} | {wall:.1f} s |")


def normal_quantile(p):
    """Phi^-1(p) by bisection on erfc (the table needs 4 digits)."""
    lo, hi = -40.0, 40.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if phi_cdf(mid) < p else (lo, mid)
    return 0.5 * (lo + hi)


if __name__ == "__main__":
    sys.exit(main())
