#!/usr/bin/env python3
"""The synthetic record generator's contract (scripts/synthetic_record.py, docs/jiufengershan.md):
the shipped Jiufengershan record is what the documented command makes, and any record it makes
has the asked PGA exactly, the asked PGV within the bisection's 1 %, and a ground that ends at
rest where it started (final velocity and displacement zero to round-off)."""
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import synthetic_record as sr  # noqa: E402

SHIPPED = ROOT / "cases" / "records" / "jiufengershan_synthetic_tcu071.csv"


def columns(path):
    rows = list(csv.reader(open(path)))
    return rows[0], np.array(rows[1:], float)


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "r.csv"
        # The command docs/jiufengershan.md gives for the shipped record.
        subprocess.run([sys.executable, str(ROOT / "scripts" / "synthetic_record.py"), str(out), "--pga", "0.655",
                        "--pgv", "69.4", "--vertical-ratio", "0.6"], check=True, stdout=subprocess.DEVNULL)
        head, made = columns(out)
        head0, shipped = columns(SHIPPED)
        if head != head0 or made.shape != shipped.shape or np.max(np.abs(made - shipped)) > 1e-6:
            failures.append("the shipped record is not what the documented command makes")
        t, ah, av = made[:, 0], made[:, 1] * sr.G, made[:, 2] * sr.G
        dt = t[1] - t[0]
        for name, a, pga in (("horizontal", ah, 0.655), ("vertical", av, 0.6 * 0.655)):
            m = sr.measures(t, a, dt)
            # The CSV's 6 significant digits: PGA to 1e-5 relative.
            if abs(m["PGA (g)"] - pga) > 1e-5 * pga:
                failures.append(f"{name} PGA {m['PGA (g)']} g, asked {pga}")
            # Zero final velocity and displacement, to the CSV's rounding (6 digits of ~6 m/s² over
            # 12000 samples: about 1e-3 cm/s and 0.05 cm).
            if abs(m["final velocity (cm/s)"]) > 0.01 or abs(m["final displacement (cm)"]) > 0.2:
                failures.append(f"{name} ground does not end at rest: {m['final velocity (cm/s)']} cm/s, "
                                f"{m['final displacement (cm)']} cm")
        pgv = sr.measures(t, ah, dt)["PGV (cm/s)"]
        if abs(pgv / 69.4 - 1) > 0.01:
            failures.append(f"horizontal PGV {pgv} cm/s, asked 69.4 within 1 %")
    for f in failures:
        print("FAIL:", f)
    print("ok" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
