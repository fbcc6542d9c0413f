#!/usr/bin/env python3
"""Writes the DXF drawings tests/test_dxf_section.cpp reads, with ezdxf (a CAD library: Debian's
python3-ezdxf), into OUTDIR, and OUTDIR/fixtures.json: for each drawing, the handle of the entity
an error must name. The build runs it (tests/CMakeLists.txt). Run: /usr/bin/python3 tests/make_dxf_fixtures.py OUTDIR

The section is the basin of tests/test_section.cpp: level ground at y = 20 m from x = 0 to 100, a
sliding surface from (10, 20) down to a seat at y = 5 and up to (90, 20) (slide mass 1050 m²), a
vertical joint at x = 50 and a water line at y = 10."""
import json, os, sys

try:
    import ezdxf
except ImportError:
    sys.exit("make_dxf_fixtures.py: ezdxf is missing: install python3-ezdxf (scripts/install-deps)")

GROUND = [(0.0, 20.0), (100.0, 20.0)]
SLIDING = [(10.0, 20.0), (20.0, 5.0), (80.0, 5.0), (90.0, 20.0)]
JOINT = ((50.0, 0.0), (50.0, 30.0))
WATER = [(0.0, 10.0), (100.0, 10.0)]
# Doubles whose decimal forms are long or inexact: the drawing must give them back to the last bit.
AWKWARD_GROUND = [(0.1 + 0.2, 1 / 3), (2 / 3, 20.000000000000004), (123.456789012345678, 19.999999999999996),
                  (1234.5678901234567, 7e-05)]
AWKWARD_SLIDING = [(0.1 + 0.2, 1 / 3), (500.0 / 7, -2.5e-7), (1234.5678901234567, 7e-05)]

handles = {}


def new(units=6):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = units
    for name in ("GROUND", "SLIP", "JOINTS", "WATER", "NOTES"):
        doc.layers.add(name)
    return doc, doc.modelspace()


def basin(msp, scale=1.0, ground=True, sliding=True, joint=True, water=True):
    s = lambda pts: [(x * scale, y * scale) for x, y in pts]
    out = {}
    if ground:
        out["ground"] = msp.add_lwpolyline(s(GROUND), dxfattribs={"layer": "GROUND"})
    if sliding:
        out["sliding"] = msp.add_lwpolyline(s(SLIDING), dxfattribs={"layer": "SLIP"})
    if joint:
        out["joint"] = msp.add_line(*s(JOINT), dxfattribs={"layer": "JOINTS"})
    if water:
        out["water"] = msp.add_line(*s(WATER), dxfattribs={"layer": "WATER"})
    return out


def save(doc, out, name, bad=None):
    doc.saveas(os.path.join(out, name + ".dxf"))
    if bad is not None:
        handles[name] = bad.dxf.handle


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    ezdxf.options.write_fixed_meta_data_for_testing = True

    doc, msp = new()
    basin(msp)
    msp.add_text("basin", dxfattribs={"layer": "NOTES", "insert": (50, 25)})
    save(doc, out, "basin")

    # The same section drawn otherwise: the ground as an old-style POLYLINE from right to left
    # with a collinear midpoint, the sliding surface as LINEs out of order and some reversed, the
    # joint as a downward LWPOLYLINE, the water line as an LWPOLYLINE from right to left; and what
    # the reader leaves alone: an unmapped layer's arc and text, the ground's layer in a block
    # definition and in paper space.
    doc, msp = new()
    msp.add_polyline2d([(100.0, 20.0), (50.0, 20.0), (0.0, 20.0)], dxfattribs={"layer": "GROUND"})
    for a, b in [((80.0, 5.0), (20.0, 5.0)), ((90.0, 20.0), (80.0, 5.0)), ((10.0, 20.0), (20.0, 5.0))]:
        msp.add_line(a, b, dxfattribs={"layer": "SLIP"})
    msp.add_lwpolyline([JOINT[1], JOINT[0]], dxfattribs={"layer": "JOINTS"})
    msp.add_lwpolyline(WATER[::-1], dxfattribs={"layer": "WATER"})
    msp.add_arc((50, 40), 5, 0, 180, dxfattribs={"layer": "NOTES"})
    msp.add_text("ignored", dxfattribs={"layer": "NOTES"})
    doc.blocks.new("TITLE").add_line((0, 0), (1000, 1000), dxfattribs={"layer": "GROUND"})
    doc.layouts.get("Layout1").add_line((0, 0), (1000, 1000), dxfattribs={"layer": "GROUND"})
    save(doc, out, "basin_drawn_otherwise")

    # Millimetres declared; a sheet at 1:1000 in mm; feet with no units declared; seen from below (extrusion (0, 0, −1):
    # the polylines' own x axis points to −x).
    doc, msp = new(units=4)
    basin(msp, scale=1000.0)
    save(doc, out, "basin_mm")
    doc, msp = new(units=4)
    basin(msp)  # 1 mm on the sheet is 1 m
    save(doc, out, "basin_sheet_1000")
    doc, msp = new(units=0)
    basin(msp, scale=1 / 0.3048)
    save(doc, out, "basin_unitless_ft")
    doc, msp = new()
    basin(msp, ground=False, sliding=False)
    for pts, layer in [(GROUND, "GROUND"), (SLIDING, "SLIP")]:
        msp.add_lwpolyline([(-x, y) for x, y in pts], dxfattribs={"layer": layer, "extrusion": (0, 0, -1)})
    save(doc, out, "basin_from_below")

    # AutoCAD R12: POLYLINE with VERTEX entities, no $INSUNITS header.
    doc = ezdxf.new("R12")
    msp = doc.modelspace()
    msp.add_polyline2d(GROUND, dxfattribs={"layer": "GROUND"})
    msp.add_polyline2d(SLIDING, dxfattribs={"layer": "SLIP"})
    msp.add_line(*JOINT, dxfattribs={"layer": "JOINTS"})
    msp.add_polyline2d(WATER, dxfattribs={"layer": "WATER"})
    save(doc, out, "basin_r12")

    doc, msp = new()
    msp.add_lwpolyline(AWKWARD_GROUND, dxfattribs={"layer": "GROUND"})
    msp.add_lwpolyline(AWKWARD_SLIDING, dxfattribs={"layer": "SLIP"})
    save(doc, out, "awkward_doubles")
    with open(os.path.join(out, "awkward_doubles.json"), "w") as f:
        json.dump({"ground": AWKWARD_GROUND, "sliding_surface": AWKWARD_SLIDING}, f)

    # Malformed drawings: each names the entity its error must name.
    doc, msp = new()
    e = basin(msp)
    e["ground"].closed = True
    save(doc, out, "closed_ground", e["ground"])

    doc, msp = new()
    basin(msp, sliding=False)
    lines = [msp.add_line(a, b, dxfattribs={"layer": "SLIP"})
             for a, b in [((10.0, 20.0), (20.0, 5.0)), ((20.0, 5.0), (90.0, 20.0)), ((90.0, 20.0), (10.0, 20.0))]]
    save(doc, out, "sliding_surface_loop", lines[0])

    doc, msp = new()
    basin(msp, ground=False)
    msp.add_line((0.0, 20.0), (40.0, 20.0), dxfattribs={"layer": "GROUND"})
    gap = msp.add_line((40.5, 20.0), (100.0, 20.0), dxfattribs={"layer": "GROUND"})
    save(doc, out, "ground_gap", gap)

    # Found by the fuzzer: a ground whose points all coincide (a line drawn as one click).
    doc, msp = new()
    basin(msp, ground=False)
    dot = msp.add_line((0.0, 20.0), (0.0, 20.0), dxfattribs={"layer": "GROUND"})
    save(doc, out, "ground_one_point", dot)

    doc, msp = new()
    basin(msp)
    arc = msp.add_arc((30, 12), 4, 0, 90, dxfattribs={"layer": "JOINTS"})
    save(doc, out, "arc_on_joints", arc)

    doc, msp = new()
    basin(msp, sliding=False)
    bulged = msp.add_lwpolyline([(10, 20, 0, 0, 0), (20, 5, 0, 0, 0.3), (80, 5, 0, 0, 0), (90, 20, 0, 0, 0)],
                                format="xyseb", dxfattribs={"layer": "SLIP"})
    save(doc, out, "arc_segment", bulged)

    doc, msp = new()
    basin(msp, ground=False)
    lifted = msp.add_line((0.0, 20.0, 0.0), (100.0, 20.0, 5.0), dxfattribs={"layer": "GROUND"})
    save(doc, out, "three_d", lifted)

    doc, msp = new(units=20)
    basin(msp)
    save(doc, out, "parsecs")

    doc, msp = new()
    basin(msp, joint=False)
    save(doc, out, "empty_joints_layer")

    doc, msp = new()
    basin(msp, joint=False)
    bent = msp.add_lwpolyline([(50.0, 0.0), (51.0, 15.0), (50.0, 30.0)], dxfattribs={"layer": "JOINTS"})
    save(doc, out, "bent_joint", bent)

    doc, msp = new()
    basin(msp, sliding=False)
    above = msp.add_lwpolyline([(10.0, 20.0), (20.0, 25.0), (80.0, 5.0), (90.0, 20.0)], dxfattribs={"layer": "SLIP"})
    save(doc, out, "sliding_surface_above_ground", above)

    doc, msp = new()
    basin(msp, water=False)
    back = msp.add_lwpolyline([(0.0, 10.0), (60.0, 12.0), (40.0, 11.0), (100.0, 10.0)], dxfattribs={"layer": "WATER"})
    save(doc, out, "water_line_back", back)

    # Files that are not sound DXF.
    with open(os.path.join(out, "basin.dxf")) as f:
        text = f.read()
    with open(os.path.join(out, "basin_crlf.dxf"), "w", newline="\r\n") as f:  # saved on Windows
        f.write(text)
    with open(os.path.join(out, "basin_blank_lines_after_eof.dxf"), "w") as f:
        f.write(text + "\n\n")
    with open(os.path.join(out, "text_after_eof.dxf"), "w") as f:  # dxflib would read it, unchecked
        f.write(text + "  0\nLWPOLYLINE\n 90\n2147483647\n")
    with open(os.path.join(out, "truncated.dxf"), "w") as f:
        f.write(text[: len(text) // 2])
    with open(os.path.join(out, "not_dxf.dxf"), "w") as f:
        f.write("ground: 0 20, 100 20\nsliding surface: 10 20, 20 5, 80 5, 90 20\n")
    with open(os.path.join(out, "binary.dxf"), "wb") as f:
        f.write(b"AutoCAD Binary DXF\r\n\x1a\x00" + bytes(range(256)))
    # An LWPOLYLINE whose vertex count (group 90) would overflow dxflib's buffer size.
    marker = "LWPOLYLINE"
    at = text.index("\n 90\n", text.index(marker))
    end = text.index("\n", at + 5)
    with open(os.path.join(out, "huge_count.dxf"), "w") as f:
        f.write(text[: at + 5] + "2147483647" + text[end:])

    with open(os.path.join(out, "fixtures.json"), "w") as f:
        json.dump(handles, f, indent=1)


if __name__ == "__main__":
    main()
