#!/usr/bin/env python3
"""Renders one frame of a `ddaslope run --vtk` series to a PNG with VTK, headless: blocks coloured
by the displacement of their centroid (fixed blocks grey), contacts coloured by state, the water
table in blue. What a ParaView user sees after opening blocks.pvd, contacts.pvd and water.pvd.

    scripts/render_vtk.py OUT/vtk docs/images/vtk_case.png [--time T] [--title TEXT]

Needs Debian's python3-vtk9 (/usr/bin/python3). Debian's VTK renders through X: without a
display the script runs itself again under xvfb-run (Debian xvfb), which is only needed here."""
import argparse, os, shutil, sys
import xml.etree.ElementTree as ET

import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

STATE_COLOURS = {0: (0.62, 0.62, 0.62), 1: (0.95, 0.50, 0.00), 2: (0.10, 0.60, 0.20)}  # open, sliding, locked
STATE_NAMES = {0: "open", 1: "sliding", 2: "locked"}


def frame(folder, kind, time):
    """The .vtu of `kind` at the series' timestep nearest `time` (None: the last), and its time."""
    pvd = os.path.join(folder, kind + ".pvd")
    if not os.path.exists(pvd):
        return None, None
    sets = [(float(d.get("timestep")), d.get("file")) for d in ET.parse(pvd).getroot().iter("DataSet")]
    t, file = sets[-1] if time is None else min(sets, key=lambda s: abs(s[0] - time))
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(folder, file))
    reader.Update()
    return reader.GetOutput(), t


def cells_where(grid, name, keep):
    """A copy of `grid` with only the cells whose array `name` satisfies keep(value)."""
    values = vtk_to_numpy(grid.GetCellData().GetArray(name))
    ids = vtk.vtkIdTypeArray()
    for c, v in enumerate(values):
        if keep(v):
            ids.InsertNextValue(c)
    selection = vtk.vtkSelectionNode()
    selection.SetFieldType(vtk.vtkSelectionNode.CELL)
    selection.SetContentType(vtk.vtkSelectionNode.INDICES)
    selection.SetSelectionList(ids)
    chosen = vtk.vtkSelection()
    chosen.AddNode(selection)
    extract = vtk.vtkExtractSelection()
    extract.SetInputData(0, grid)
    extract.SetInputData(1, chosen)
    extract.Update()
    return extract.GetOutput()


def actor_of(data, colour=None, scalars=None, lut=None, line_width=None, lift=0.0):
    """An actor drawing `data`; `lift` raises it toward the camera (drawn over what lies below)."""
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputData(data)
    if scalars:
        mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray(scalars)
        mapper.SetLookupTable(lut)
        mapper.UseLookupTableScalarRangeOn()
        mapper.ScalarVisibilityOn()
    else:
        mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.SetPosition(0, 0, lift)
    if colour:
        actor.GetProperty().SetColor(*colour)
    if line_width:
        actor.GetProperty().SetLineWidth(line_width)
        actor.GetProperty().RenderLinesAsTubesOn()
    return actor


def filled(grid):
    """`grid`'s polygons as triangles: VTK draws a polygon as a fan from its first vertex, which
    fills a concave block (the ground of a section) wrong; ParaView's Triangulate filter is the
    same cure."""
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    triangles = vtk.vtkTriangleFilter()
    triangles.SetInputConnection(surface.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def outlines(grid):
    edges = vtk.vtkExtractEdges()
    edges.SetInputData(grid)
    edges.Update()
    return edges.GetOutput()


def text(renderer, message, x, y, size=18, colour=(0, 0, 0)):
    t = vtk.vtkTextActor()
    t.SetInput(message)
    t.GetTextProperty().SetFontSize(size)
    t.GetTextProperty().SetColor(*colour)
    t.SetDisplayPosition(x, y)
    renderer.AddActor2D(t)


def render(folder, png, time=None, title="", width=1400):
    blocks, t = frame(folder, "blocks", time)
    if blocks is None:
        sys.exit(f"{folder}: no blocks.pvd (write one with ddaslope run CASE --out DIR --vtk)")
    contacts, _ = frame(folder, "contacts", t)
    water, _ = frame(folder, "water", t)
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)

    # Blocks: free ones by |displacement| (blue still to red the most moved), fixed ones grey.
    u = vtk_to_numpy(blocks.GetCellData().GetArray("displacement"))
    fixed = vtk_to_numpy(blocks.GetCellData().GetArray("fixed"))
    magnitude = numpy_to_vtk((u ** 2).sum(axis=1) ** 0.5, deep=True)
    magnitude.SetName("displacement_magnitude")
    blocks.GetCellData().AddArray(magnitude)
    largest = max([m for m, f in zip(vtk_to_numpy(magnitude), fixed) if not f] + [1e-12])
    lut = vtk.vtkLookupTable()
    lut.SetTableRange(0, largest)
    lut.SetHueRange(0.62, 0.0)  # blue to red
    lut.SetSaturationRange(0.75, 0.85)
    lut.SetValueRange(0.85, 0.9)
    lut.Build()
    free, still = (cells_where(blocks, "fixed", keep) for keep in (lambda f: f == 0, lambda f: f != 0))
    renderer.AddActor(actor_of(filled(free), scalars="displacement_magnitude", lut=lut))
    renderer.AddActor(actor_of(filled(still), colour=(0.80, 0.80, 0.80)))
    lift = 1e-3 * (blocks.GetBounds()[1] - blocks.GetBounds()[0])
    renderer.AddActor(actor_of(outlines(blocks), colour=(0.15, 0.15, 0.15), line_width=1.5, lift=lift))

    # Contacts: one line each from the contact vertex into its block, coloured by state.
    counts = {}
    if contacts is not None and contacts.GetNumberOfCells() > 0:
        states = vtk_to_numpy(contacts.GetCellData().GetArray("state"))
        for s, colour in STATE_COLOURS.items():
            n = int((states == s).sum())
            counts[s] = n
            if n:
                a = actor_of(cells_where(contacts, "state", lambda v, s=s: v == s), colour=colour, line_width=4,
                             lift=2 * lift)
                renderer.AddActor(a)
    if water is not None and water.GetNumberOfCells() > 0:
        renderer.AddActor(actor_of(water, colour=(0.15, 0.45, 0.95), line_width=3, lift=3 * lift))

    # A flat 2-D view: the blocks fill the width, with a title strip above and a legend below.
    x0, x1, y0, y1, _, _ = blocks.GetBounds()
    top, bottom = 60, 130
    scale = 1.04 * (x1 - x0) / width  # world length per pixel
    height = int((y1 - y0) / scale * 1.02) + top + bottom
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    centre = ((x0 + x1) / 2, y0 - 0.01 * (y1 - y0) - bottom * scale + 0.5 * height * scale)
    camera.SetFocalPoint(centre[0], centre[1], 0)
    camera.SetPosition(centre[0], centre[1], 10 * (x1 - x0))  # far above the lifted lines
    camera.SetViewUp(0, 1, 0)
    camera.SetParallelScale(0.5 * height * scale)
    renderer.ResetCameraClippingRange()

    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle("")
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%.3g")
    bar.SetOrientationToHorizontal()
    bar.UnconstrainedFontSizeOn()  # fixed font sizes, not scaled with the bar
    bar.SetPosition(0.55, 10 / height)
    bar.SetWidth(0.4)
    bar.SetHeight(60 / height)
    bar.GetLabelTextProperty().SetColor(0, 0, 0)
    bar.GetLabelTextProperty().SetFontSize(16)
    bar.GetLabelTextProperty().ShadowOff()
    bar.GetLabelTextProperty().ItalicOff()
    bar.GetLabelTextProperty().BoldOff()
    renderer.AddActor2D(bar)
    text(renderer, "block displacement (m), fixed blocks grey", int(0.55 * width), 78, 18)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(width, height)
    text(renderer, f"{title}  t = {t:.4g} s" if title else f"t = {t:.4g} s", 20, height - 40, 20)
    text(renderer, "contacts (a line from the contact vertex into its block):", 20, 78, 18)
    x = 20
    for s in (2, 1, 0):
        text(renderer, f"\u2014\u2014 {STATE_NAMES[s]} {counts.get(s, 0)}", x, 46, 18, STATE_COLOURS[s])
        x += 150
    if water is not None and water.GetNumberOfCells() > 0:
        text(renderer, "\u2014\u2014 water table", x, 46, 18, (0.15, 0.45, 0.95))
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    out = vtk.vtkPNGWriter()
    out.SetFileName(png)
    out.SetInputConnection(image.GetOutputPort())
    out.Write()
    print(f"wrote {png} ({width} x {height} px, t = {t:.6g} s)")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("folder", help="the series' folder: RUN_OUT/vtk")
    p.add_argument("png", help="picture to write")
    p.add_argument("--time", type=float, help="the frame nearest this time (default: the last)")
    p.add_argument("--title", default="", help="text at the top")
    p.add_argument("--width", type=int, default=1400, help="pixels")
    args = p.parse_args()
    if not os.environ.get("DISPLAY") and not os.environ.get("DDASLOPE_UNDER_XVFB"):
        xvfb = shutil.which("xvfb-run")
        if not xvfb:
            sys.exit("no display and no xvfb-run: install Debian's xvfb (apt-get install xvfb)")
        os.environ["DDASLOPE_UNDER_XVFB"] = "1"
        os.execv(xvfb, [xvfb, "-a", "-s", "-screen 0 1920x1080x24", sys.executable] + sys.argv)
    render(args.folder, args.png, args.time, args.title, args.width)


if __name__ == "__main__":
    main()
