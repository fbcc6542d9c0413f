#!/usr/bin/env python3
"""Print the markdown tables of docs/research/kink-blocks.md from results.jsonl."""
import json, re, os
R = [json.loads(l) for l in open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "results.jsonl"))]
def find(item, kind, **lab):
    out = [r for r in R if r["item"] == item and r["kind"] == kind and all(r["label"].get(k) == v for k, v in lab.items())]
    return out[-1] if out else None
# chair
le = {}
for off in [0.0, 10.0, 25.0, 40.0]:
    r = find("chair", "le", offset=off)
    le[off] = float(re.search(r"interface friction 40 deg: critical cohesion ([0-9.]+) kPa", r["stdout"]).group(1))
W = [(0.0, "none (0)"), (1.4375, "2.5e-3 w0 = 1.44 m"), (2.875, "5e-3 w0 = 2.875 m (≈ 5 % of thickness, 2.89 m)"), (5.75, "1e-2 w0 = 5.75 m"), (3.0, "3 m (shipped)")]
print("| kink block width | offset 0 m | 10 m | 25 m | 40 m | spread over offsets | worst against slices |")
print("|---|---|---|---|---|---|---|")
for w, name in W:
    cells, cs, devs = [], [], []
    for off in [0.0, 10.0, 25.0, 40.0]:
        c = find("chair", "critical", offset=off, w=w)["critical"] / 1e3
        b = find("chair", "bound", offset=off, w=w)["result"]["value"] / 1e3
        d = 100 * (c - le[off]) / le[off]
        cs.append(c); devs.append(d)
        cells.append(f"{c:.2f} ({d:+.1f} %; bound {b:.1f})")
    print(f"| {name} | " + " | ".join(cells) + f" | {min(cs):.2f}–{max(cs):.2f} | {max(devs, key=abs):+.1f} % |")
print("\nslices (multi-wedge, δ = 40°):", {k: v for k, v in le.items()})
# vajont
print("\n| kink block width | offset 0 (shipped joints) | 10 m | 25 m | 40 m |")
print("|---|---|---|---|---|")
for w, name in [(0.0, "none (0)"), (2.175, "2.5e-3 w0 = 2.175 m"), (4.35, "5e-3 w0 = 4.35 m"), (8.7, "1e-2 w0 = 8.7 m"), (10.0, "10 m (shipped)")]:
    cells = []
    for off in [None, 10.0, 25.0, 40.0]:
        c = find("vajont", "critical", offset=off, w=w) if off else next((r for r in R if r["item"] == "vajont" and r["kind"] == "critical" and r["label"] == {"w": w}), None)
        b = find("vajont", "bound", offset=off, w=w) if off else next((r for r in R if r["item"] == "vajont" and r["kind"] == "bound" and r["label"] == {"w": w}), None)
        cells.append(f"{c['critical']:.3f}° (bound {b['result']['value']:.3f}°)" if c and b else "–")
    print(f"| {name} | " + " | ".join(cells) + " |")
for r in R:
    if r["item"] == "vajont" and isinstance(r["label"].get("w"), str):
        print(r["kind"], r["label"], r.get("critical"), (r.get("result") or {}).get("value"))
# jiuf
print("\n| kink block width | critical φ before shaking | blocks' bound |")
print("|---|---|---|")
for r in R:
    if r["item"] == "jiuf" and r["kind"] == "critical":
        print(f"| {r['label']['w']:g} m | {r['critical']:.2f}° | |")
for r in R:
    if r["item"] == "jiuf" and r["kind"] == "bound":
        print(r["label"], r["result"]["value"])
print()
for r in R:
    if r["kind"] == "critical":
        print(r["item"], r["label"], r["cmd"])
