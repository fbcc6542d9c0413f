#!/usr/bin/env python3
"""Markdown tables of docs/accuracy.md from the CSV of build/ddaslope_accuracy.
Run: build/ddaslope_accuracy --out out/accuracy && python3 scripts/accuracy_tables.py out/accuracy/accuracy.csv"""
import csv, sys


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    print(f"{len(rows)} settings\n")
    print("| quantity | deformable blocks | rigid blocks |")
    print("|---|---|---|")
    names = {"sliding_error": "A2 sliding, relative error", "stable_error": "A3 stable, displacement / b",
             "cohesion_error": "B1 critical cohesion, relative error", "fos_error": "C planar F, relative error",
             "toppling_error": "A6 toppling, relative error", "two_block_error_vs_finest": "two-block slide, against the finest",
             "wall_s": "wall time of the six (s)"}
    for col, name in names.items():
        cells = []
        for b in ("deformable", "rigid"):
            v = [float(r[col]) for r in rows if r["blocks"] == b]
            cells.append(f"{min(v):.2g} to {max(v):.2g}")
        print(f"| {name} | {cells[0]} | {cells[1]} |")
    print()
    for b in ("deformable", "rigid"):
        for limit in ("30", "6"):
            print(f"Two-block slide error (%), {b} blocks, open-close limit {limit}; cells: penalty factor 10 / 40 / 100\n")
            print("| Δt | g2 = 0.002 | g2 = 0.005 | g2 = 0.01 | wall time (s) |")
            print("|---|---|---|---|---|")
            for dt in ("0.01", "0.003", "0.001", "0.0003"):
                cells, walls = [], []
                for g2 in ("0.002", "0.005", "0.01"):
                    part = []
                    for pf in ("10", "40", "100"):
                        r = next(r for r in rows if r["time_step"] == dt and r["max_displacement_ratio"] == g2
                                 and r["penalty_factor"] == pf and r["open_close_limit"] == limit and r["blocks"] == b)
                        part.append(f"{100 * float(r['two_block_error_vs_finest']):.2g}")
                        walls.append(float(r["wall_s"]))
                    cells.append(" / ".join(part))
                print(f"| {float(dt) * 1e3:g} ms | {' | '.join(cells)} | {min(walls):.2f}–{max(walls):.2f} |")
            print()
    front = [r for r in rows if r["pareto"] == "1"]
    print("Pareto front:", "; ".join(f"Δt {r['time_step']} s, g2 {r['max_displacement_ratio']}, penalty ×{r['penalty_factor']}, "
                                     f"limit {r['open_close_limit']}, {r['blocks']}: worst {float(r['worst_error']):.3g} in {r['wall_s']} s"
                                     for r in front))


if __name__ == "__main__":
    main()
