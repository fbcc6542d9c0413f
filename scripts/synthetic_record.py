#!/usr/bin/env python3
"""A synthetic accelerogram matched to a site's published peak ground acceleration and velocity.

Where no recorded accelerogram of a site is available offline (issue #17, item 7), the case runs on
a documented synthetic one. This script makes it, reproducibly from a seed:

1. white noise (numpy's PCG64 generator, `--seed`), sampled at `--dt`;
2. filtered by the Clough–Penzien spectrum: a Kanai–Tajimi soil filter (f_g, ζ_g) followed by a
   high-pass (f_f, ζ_f) that removes the filter's non-zero response at zero frequency;
3. shaped by a Jennings-type envelope: a quadratic rise to `--rise`, flat to `--flat-end`, then
   exp(−`--decay`·(t − flat_end)), to `--duration`;
4. baseline-corrected as processed records are: a zero-phase 4th-order Butterworth high-pass at
   `--highpass` Hz, then the cubic that fits the displacement removed (its second derivative from
   the acceleration), then a line in the acceleration that brings the final velocity and
   displacement to zero: the ground ends at rest where it started;
5. scaled to the target PGA.

The velocity content is set by f_g: with `--pgv` the script finds the f_g (bisection over 0.3–8
Hz, same seed) whose record, scaled to the PGA, has that PGV (within 1 %). The vertical
component, if asked for (`--vertical-ratio`), uses its own seed (seed + 1), the same filter and
envelope, scaled to that ratio of the horizontal PGA.

Writes a CSV `time,a_h[,a_v]` in g (ddaslope's `seismic.record` with `"units": "g"`) and prints
the record's measures: PGA, PGV, peak ground displacement, final velocity and displacement, Arias
intensity, the 5–95 % significant duration and the bracketed duration above 0.05 g.

usage: synthetic_record.py OUT.csv --pga 0.655 --pgv 69.4 [--vertical-ratio 0.6] [--seed 1999]
Needs numpy and scipy (python3-numpy, python3-scipy).
"""
import argparse
import math
import sys

import numpy as np
from scipy import signal

G = 9.80665


def envelope(t, rise, flat_end, decay):
    e = np.ones_like(t)
    e[t < rise] = (t[t < rise] / rise) ** 2
    late = t > flat_end
    e[late] = np.exp(-decay * (t[late] - flat_end))
    return e


def clough_penzien(noise, dt, fg, zg, ff, zf):
    """Filters white noise by the Clough–Penzien transfer function (ground acceleration)."""
    n = len(noise)
    w = 2 * np.pi * np.fft.rfftfreq(n, dt)
    wg, wf = 2 * np.pi * fg, 2 * np.pi * ff
    kanai = (wg ** 2 + 2j * zg * wg * w) / (wg ** 2 - w ** 2 + 2j * zg * wg * w)
    highpass = -w ** 2 / (wf ** 2 - w ** 2 + 2j * zf * wf * w)
    return np.fft.irfft(np.fft.rfft(noise) * kanai * highpass, n)


def baseline_corrected(a, dt, corner):
    """High-pass, then the cubic that fits the displacement removed (its second derivative from
    the acceleration): the ground ends at rest where it started, as a processed record does."""
    sos = signal.butter(4, corner, btype="highpass", fs=1 / dt, output="sos")
    a = signal.sosfiltfilt(sos, a)
    t = np.arange(len(a)) * dt
    for _ in range(3):  # the trapezoidal integration is not exact for the polynomial's own samples
        _, d = integrate(a, dt)
        c = np.polyfit(t, d, 3)
        a = a - np.polyval(np.polyder(c, 2), t)
        v, d = integrate(a, dt)
        # the remaining final velocity and displacement, by a line p + q t in the acceleration
        big_t = t[-1]
        p, q = np.linalg.solve([[big_t, big_t ** 2 / 2], [big_t ** 2 / 2, big_t ** 3 / 6]], [v[-1], d[-1]])
        a = a - (p + q * t)
    return a


def integrate(a, dt):
    """Velocity and displacement by the trapezoidal rule, from rest."""
    v = np.concatenate([[0.0], np.cumsum((a[1:] + a[:-1]) / 2) * dt])
    d = np.concatenate([[0.0], np.cumsum((v[1:] + v[:-1]) / 2) * dt])
    return v, d


def component(o, seed, fg, pga_g):
    t = np.arange(int(round(o.duration / o.dt)) + 1) * o.dt
    noise = np.random.Generator(np.random.PCG64(seed)).standard_normal(len(t))
    a = clough_penzien(noise, o.dt, fg, o.zeta_g, o.f_f, o.zeta_f) * envelope(t, o.rise, o.flat_end, o.decay)
    a = baseline_corrected(a, o.dt, o.highpass)
    return t, a * pga_g * G / np.max(np.abs(a))  # m/s²


def measures(t, a, dt):
    v, d = integrate(a, dt)
    arias = math.pi / (2 * G) * np.cumsum(a ** 2) * dt
    i5, i95 = np.searchsorted(arias, 0.05 * arias[-1]), np.searchsorted(arias, 0.95 * arias[-1])
    above = np.nonzero(np.abs(a) >= 0.05 * G)[0]
    return {
        "PGA (g)": np.max(np.abs(a)) / G,
        "PGV (cm/s)": 100 * np.max(np.abs(v)),
        "PGD (cm)": 100 * np.max(np.abs(d)),
        "final velocity (cm/s)": 100 * v[-1],
        "final displacement (cm)": 100 * d[-1],
        "Arias intensity (m/s)": arias[-1],
        "D5-95 (s)": t[i95] - t[i5],
        "bracketed duration > 0.05 g (s)": (t[above[-1]] - t[above[0]]) if len(above) else 0.0,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--pga", type=float, required=True, help="horizontal PGA (g)")
    ap.add_argument("--pgv", type=float, help="target horizontal PGV (cm/s): sets f_g")
    ap.add_argument("--f-g", type=float, default=1.5, help="Kanai-Tajimi frequency (Hz), without --pgv")
    ap.add_argument("--zeta-g", type=float, default=0.6)
    ap.add_argument("--f-f", type=float, default=0.15, help="Clough-Penzien high-pass frequency (Hz)")
    ap.add_argument("--zeta-f", type=float, default=0.6)
    ap.add_argument("--rise", type=float, default=5.0, help="end of the quadratic rise (s)")
    ap.add_argument("--flat-end", type=float, default=17.0, help="end of the strong phase (s)")
    ap.add_argument("--decay", type=float, default=0.25, help="decay rate after it (1/s)")
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--dt", type=float, default=0.005)
    ap.add_argument("--highpass", type=float, default=0.1, help="baseline-correction corner (Hz)")
    ap.add_argument("--vertical-ratio", type=float, default=0.0, help="vertical PGA / horizontal PGA (0: none)")
    ap.add_argument("--seed", type=int, default=1999)
    o = ap.parse_args()

    fg = o.f_g
    if o.pgv is not None:
        lo, hi = 0.3, 8.0  # PGV falls as f_g rises
        pgv = lambda f: measures(*component(o, o.seed, f, o.pga), o.dt)["PGV (cm/s)"]
        if not pgv(hi) <= o.pgv <= pgv(lo):
            sys.exit(f"synthetic_record: PGV {o.pgv} cm/s is outside what f_g in [{lo}, {hi}] Hz gives "
                     f"({pgv(hi):.1f}-{pgv(lo):.1f} cm/s) with this seed and envelope")
        for _ in range(40):
            fg = math.sqrt(lo * hi)
            if pgv(fg) > o.pgv:
                lo = fg
            else:
                hi = fg
            if abs(pgv(fg) / o.pgv - 1) < 0.01:
                break
    t, ah = component(o, o.seed, fg, o.pga)
    columns, header = [t, ah / G], "time,a_h"
    print(f"f_g = {fg:.4f} Hz (zeta_g {o.zeta_g}), f_f = {o.f_f} Hz (zeta_f {o.zeta_f}), seed {o.seed}, "
          f"{len(t)} samples at {o.dt} s")
    for k, v in measures(t, ah, o.dt).items():
        print(f"  horizontal {k}: {v:.4g}")
    if o.vertical_ratio > 0:
        _, av = component(o, o.seed + 1, fg, o.vertical_ratio * o.pga)
        columns.append(av / G)
        header += ",a_v"
        for k, v in measures(t, av, o.dt).items():
            print(f"  vertical {k}: {v:.4g}")
    with open(o.out, "w") as f:
        f.write(header + "\n")
        for row in zip(*columns):
            f.write(",".join(f"{x:.6g}" for x in row) + "\n")
    print(f"wrote {o.out}")


if __name__ == "__main__":
    main()
