#!/usr/bin/env python3
"""The creep of a block just past its limit, against the closed form, by block model, contact
treatment, strain damping and Δt (docs/accuracy.md, "Strain damping and friction flutter").

A3's 10 x 10 m block on a 40° plane (cases/stable_block_40deg.json) with φ = 39.9°: it slides with
a = g (sin α − cos α tan φ), 0.045501 m in 2 s. Prints a markdown table of the monitor's
displacement at 2 s and its error.

usage: creep_table.py [DDASLOPE] [--time-steps 0.01,0.001,0.0002]   (about 30 s)
"""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "stable_block_40deg.json"


def displacement(exe, out, *options):
    cmd = [exe, "run", str(CASE), "--quiet", "--out", out, "--set", "joints.interface.friction_angle=39.9", *options]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads((Path(out) / "summary.json").read_text())["expected"][0]["actual"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ddaslope", nargs="?", default=str(ROOT / "build" / "ddaslope"))
    ap.add_argument("--time-steps", default="0.01,0.001,0.0002")
    o = ap.parse_args()
    steps = [float(s) for s in o.time_steps.split(",")]
    alpha, phi = math.radians(40), math.radians(39.9)
    exact = 0.5 * 10 * (math.sin(alpha) - math.cos(alpha) * math.tan(phi)) * 2 ** 2
    rows = [("rigid", "edge", None), ("deformable", "edge", 0), ("deformable", "edge", 0.3),
            ("deformable", "edge", 1), ("deformable", "vertex", 0), ("deformable", "vertex", 1)]
    print(f"closed form: {exact:.5f} m in 2 s\n")
    print("| blocks | contact treatment | strain damping | " + " | ".join(f"Δt {1e3 * s:g} ms" for s in steps) + " |")
    print("|---|---|---|" + "---|" * len(steps))
    with tempfile.TemporaryDirectory() as out:
        for blocks, treatment, xi in rows:
            cells = []
            for dt in steps:
                options = ["--blocks", blocks, "--contact-treatment", treatment, "--time-step", str(dt)]
                if xi is not None:
                    options += ["--set", f"analysis.strain_damping={xi}"]
                d = displacement(o.ddaslope, out, *options)
                cells.append(f"{d:.4f} ({100 * (d / exact - 1):+.1f} %)")
            print(f"| {blocks} | {treatment} | {'–' if xi is None else xi} | " + " | ".join(cells) + " |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
