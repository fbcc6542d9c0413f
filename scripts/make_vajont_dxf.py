#!/usr/bin/env python3
"""Draws the Vajont section of cases/vajont.json as a CAD drawing, cases/vajont_section.dxf, and
writes cases/vajont_dxf.json: the same case with its section read from that drawing (issue #19).

The drawing is what an engineer would hand over: metres ($INSUNITS 6), the ground surface and the
sliding surface as polylines on layers GROUND and SLIP_SURFACE, the joint at the lower kink as a
line on JOINTS, the reservoir level at failure as a line on WATER, and labels on ANNOTATION
(which the case does not map, so ddaslope leaves it alone). The joint set, the kink blocks, the
materials and everything else stay in the case. Coordinates are written with Python's shortest
round-trip repr, so the drawing holds the very doubles of the JSON section and cuts into the same
blocks (tests/test_dxf_section.cpp).

Needs ezdxf (Debian: python3-ezdxf; scripts/install-deps). Run: /usr/bin/python3 scripts/make_vajont_dxf.py
The output is byte-identical from run to run (ezdxf's fixed metadata), so a change shows in git."""
import argparse, copy, json, os

import ezdxf

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, "..", "cases")
LAYERS = {"GROUND": 3, "SLIP_SURFACE": 1, "JOINTS": 5, "WATER": 4, "ANNOTATION": 7}  # AutoCAD colour numbers


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=os.path.join(CASES, "vajont.json"), help="the JSON case whose section is drawn")
    ap.add_argument("--dxf", default=os.path.join(CASES, "vajont_section.dxf"))
    ap.add_argument("--out", default=os.path.join(CASES, "vajont_dxf.json"))
    a = ap.parse_args()
    case = json.load(open(a.case))
    section = case["section"]
    level = case["water"]["level"]

    ezdxf.options.write_fixed_meta_data_for_testing = True  # no creation time or random GUIDs
    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.M  # $INSUNITS 6
    doc.header["$MEASUREMENT"] = 1  # metric
    for name, colour in LAYERS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    msp.add_lwpolyline(section["ground"], format="xy", dxfattribs={"layer": "GROUND"})
    msp.add_lwpolyline(section["sliding_surface"], format="xy", dxfattribs={"layer": "SLIP_SURFACE"})
    for p, q in section["joints"]:
        msp.add_line(p, q, dxfattribs={"layer": "JOINTS"})
    x0, x1 = section["ground"][0][0], section["ground"][-1][0]
    msp.add_line((x0, level), (x1, level), dxfattribs={"layer": "WATER"})
    notes = [((20, 600), "Vajont 1963, section after Boon, Houlsby & Utili (2014); y = 0 at 630 m a.s.l."),
             ((1250, level + 8), f"reservoir at failure, {level + 630:.2f} m a.s.l."),
             ((700, 40), "sliding surface (c = 0, phi back-analysed)")]
    for at, text in notes:
        msp.add_text(text, dxfattribs={"layer": "ANNOTATION", "height": 8, "insert": at})
    doc.saveas(a.dxf)

    dxf_case = copy.deepcopy(case)
    dxf_case["description"] = (
        "Vajont (Vaiont) rockslide, 9 Oct 1963: cases/vajont.json with its section drawn in CAD "
        "(vajont_section.dxf: ground, sliding surface, the joint at the lower kink and the reservoir level at "
        "failure on layers GROUND, SLIP_SURFACE, JOINTS and WATER, in metres); the joint set, kink blocks, "
        "materials, monitors and analysis are the JSON case's. It cuts into the same blocks as cases/vajont.json "
        "(tests/test_dxf_section.cpp). Sources and reconstructions: cases/vajont.json. "
        "Regenerate: scripts/make_vajont_dxf.py")
    drawn = {"dxf": {"file": os.path.relpath(a.dxf, os.path.dirname(os.path.abspath(a.out))), "units": "m",
                     "scale": 1.0,
                     "layers": {"ground": "GROUND", "sliding_surface": "SLIP_SURFACE", "joints": "JOINTS",
                                "water_line": "WATER"}}}
    dxf_case["section"] = {**drawn, **{k: v for k, v in section.items()
                                       if k not in ("ground", "sliding_surface", "joints")}}
    water = {k: v for k, v in case["water"].items() if k != "level"}  # the reservoir level is drawn
    if water:
        dxf_case["water"] = water
    else:
        del dxf_case["water"]
    with open(a.out, "w") as f:
        json.dump(dxf_case, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
