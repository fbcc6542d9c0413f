#!/usr/bin/env python3
"""Reads the VTK series that `run --vtk` and a search's `--vtk` write with VTK's own reader
(vtkXMLUnstructuredGridReader, Debian python3-vtk9) and checks them against the run's own
history.csv, the case files and closed forms (run by ctest when `import vtk` works)."""
import csv, filecmp, glob, json, math, os, subprocess, sys, tempfile, unittest
import xml.etree.ElementTree as ET

import vtk
from vtk.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DDASLOPE = os.environ.get("DDASLOPE_CLI", os.path.join(ROOT, "build", "ddaslope"))

VTK_POLYGON, VTK_LINE, VTK_POLY_LINE = 7, 3, 4
OPEN, SLIDING, LOCKED = 0, 1, 2  # the `state` codes docs/case-format.md promises


def case_path(name):
    return os.path.join(ROOT, "cases", name)


def load_case(name):
    with open(case_path(name)) as f:
        return json.load(f)


def run(args):
    subprocess.run([DDASLOPE] + args, check=True, stdout=subprocess.DEVNULL)


def series(pvd):
    """[(timestep, path)] of a .pvd, in the file's order (no vtkPVDReader outside ParaView)."""
    root = ET.parse(pvd).getroot()
    assert root.get("type") == "Collection"
    folder = os.path.dirname(pvd)
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in root.iter("DataSet")]


class Grid:
    """One .vtu as VTK reads it: cell arrays as numpy arrays, field data as lists."""

    def __init__(self, path):
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(path)
        reader.Update()
        if reader.GetErrorCode() != 0:
            raise AssertionError(f"VTK could not read {path}")
        self.grid = reader.GetOutput()
        cells = self.grid.GetCellData()
        self.cells = {cells.GetArrayName(i): vtk_to_numpy(cells.GetArray(i)) for i in range(cells.GetNumberOfArrays())}
        fields = self.grid.GetFieldData()
        self.field = {}
        for i in range(fields.GetNumberOfArrays()):
            a = fields.GetAbstractArray(i)
            self.field[a.GetName()] = [a.GetValue(k) for k in range(a.GetNumberOfValues())]

    def count(self):
        return self.grid.GetNumberOfCells()

    def types(self):
        return {self.grid.GetCellType(c) for c in range(self.count())}


def last_row(history):
    with open(history) as f:
        return list(csv.DictReader(f))[-1]


def printed(value, digits=12):
    """One unit in the last digit history.csv prints (%.12g) at this value."""
    return 10 ** (math.floor(math.log10(abs(value))) - digits + 1) if value else 1e-300


def rectangle_centre(vertices):
    """The centroid of the cases' rectangular blocks: the mean of their four corners."""
    assert len(vertices) == 4
    return sum(v[0] for v in vertices) / 4, sum(v[1] for v in vertices) / 4


class RunSeries(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        out = cls.tmp.name
        # A2: a 10 x 5 m block sliding on a 40 deg plane with phi = 20 deg (2 s, 2000 steps).
        run(["run", case_path("sliding_block_40deg.json"), "--out", f"{out}/plain", "--quiet"])
        run(["run", case_path("sliding_block_40deg.json"), "--out", f"{out}/slide", "--quiet", "--vtk"])
        # A3: the same block at phi = 40.1 deg stands; A6: a 10 x 25 m block topples (rigid: its
        # top corner then moves exactly with the centroid and the rotation).
        run(["run", case_path("stable_block_40deg.json"), "--out", f"{out}/stand", "--quiet", "--vtk",
             "--vtk-every", "0.5"])
        run(["run", case_path("toppling_block.json"), "--out", f"{out}/topple", "--quiet", "--vtk", "--blocks", "rigid"])
        run(["run", case_path("planar_failure_water.json"), "--out", f"{out}/water", "--quiet", "--vtk",
             "--duration", "0.1"])
        run(["run", case_path("goodman_bray_toppling_anchor.json"), "--out", f"{out}/anchor", "--quiet", "--vtk",
             "--duration", "0.1"])
        cls.out = out

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def final(self, run_name, kind):
        return Grid(series(f"{self.out}/{run_name}/vtk/{kind}.pvd")[-1][1])

    def test_history_is_the_same_with_and_without_vtk(self):
        self.assertTrue(filecmp.cmp(f"{self.out}/plain/history.csv", f"{self.out}/slide/history.csv", shallow=False))

    def test_series_lists_its_frames_in_time_order(self):
        # Default cadence: a hundredth of the 2 s run, with t = 0 and the final state: 101 frames.
        for kind in ("blocks", "contacts"):
            frames = series(f"{self.out}/slide/vtk/{kind}.pvd")
            self.assertEqual(len(frames), 101)
            times = [t for t, _ in frames]
            self.assertEqual(times[0], 0.0)
            self.assertEqual(times[-1], 2.0)  # analysis.duration of the case
            self.assertEqual(times, sorted(times))
            for t, path in frames:
                self.assertTrue(os.path.exists(path), path)
        # --vtk-every 0.5 over the 2 s of A3: t = 0, 0.5, 1, 1.5, 2 (each the first step at or after).
        frames = series(f"{self.out}/stand/vtk/blocks.pvd")
        self.assertEqual([round(t, 9) for t, _ in frames], [0, 0.5, 1, 1.5, 2])
        self.assertFalse(os.path.exists(f"{self.out}/slide/vtk/water.pvd"))  # a dry case: no water series

    def test_block_count_names_and_the_monitor_block_displacement(self):
        case = load_case("sliding_block_40deg.json")
        blocks = self.final("slide", "blocks")
        self.assertEqual(blocks.count(), len(case["blocks"]))  # 2: the fixed ramp and the block
        self.assertEqual(blocks.types(), {VTK_POLYGON})
        self.assertEqual(blocks.field["block_names"], [b["id"] for b in case["blocks"]])
        self.assertEqual(blocks.field["material_names"], list(case["materials"]))
        self.assertEqual(blocks.field["TimeValue"], [2.0])
        # The monitor "centre" is the block's centroid (the case's point is the mean of its
        # rectangle's corners), so the block's displacement and velocity are the monitor's in
        # history.csv, to the 12 significant digits it prints (two units of the last: one for
        # the print, one for the round-off of 2000 steps).
        monitor = case["monitors"][0]
        vertices = next(b["vertices"] for b in case["blocks"] if b["id"] == monitor["block"])
        self.assertLess(math.dist(rectangle_centre(vertices), monitor["point"]), 1e-11)
        b = blocks.field["block_names"].index(monitor["block"])
        row = last_row(f"{self.out}/slide/history.csv")
        for array, column in (("displacement", "_u"), ("velocity", "_v")):
            for k, axis in enumerate("xy"):
                want = float(row[monitor["id"] + column + axis])
                self.assertLess(abs(blocks.cells[array][b][k] - want), 2 * printed(want), (array, axis))
            self.assertEqual(blocks.cells[array][b][2], 0.0)
        # The fixed ramp never moves; deformable blocks carry stress, the fixed ramp none.
        ramp = blocks.field["block_names"].index("ramp")
        self.assertEqual(blocks.cells["fixed"][ramp], 1)
        self.assertTrue((blocks.cells["displacement"][ramp] == 0).all())
        self.assertTrue((blocks.cells["stress"][ramp] == 0).all())
        self.assertGreater(abs(blocks.cells["stress"][b]).max(), 0)

    def test_a_stopped_run_leaves_a_series_to_its_last_state(self):
        # analysis.max_steps = 50 stops A2 at t = 0.05 s (exit 3, a spent budget): the series holds
        # t = 0, 0.02, 0.04 and the state it stopped in, which is history.partial.csv's last row.
        out = f"{self.out}/stopped"
        code = subprocess.run([DDASLOPE, "run", case_path("sliding_block_40deg.json"), "--out", out, "--quiet", "--vtk",
                               "--set", "analysis.max_steps=50"], capture_output=True).returncode
        self.assertEqual(code, 3)
        frames = series(f"{out}/vtk/blocks.pvd")
        self.assertEqual([round(t, 9) for t, _ in frames], [0, 0.02, 0.04, 0.05])
        row = last_row(f"{out}/history.partial.csv")
        self.assertEqual(float(row["time"]), 0.05)
        u = Grid(frames[-1][1]).cells["displacement"][1]
        for k, axis in enumerate("xy"):
            want = float(row["centre_u" + axis])
            self.assertLess(abs(u[k] - want), 2 * printed(want), axis)

    def test_sliding_block_contacts_slide_under_friction(self):
        contacts = self.final("slide", "contacts")
        self.assertEqual(contacts.types(), {VTK_LINE})
        self.assertGreater(contacts.count(), 0)
        # phi = 20 deg < 40 deg: every contact of the block on the ramp slides (case A2), ...
        self.assertTrue((contacts.cells["state"] == SLIDING).all(), contacts.cells["state"])
        # ... pressed by N = W cos a and resisted by S = N tan phi in total (closed form of A2:
        # W = 2000 kg/m3 x 10 m/s2 x 50 m2; 0.1 %: the contact springs' vibration about it).
        w, a, phi = 2000 * 10 * 50, math.radians(40), math.radians(20)
        n, s = contacts.cells["normal_force"].sum(), contacts.cells["shear_force"].sum()
        self.assertAlmostEqual(n / (w * math.cos(a)), 1, delta=1e-3)
        self.assertAlmostEqual(s / (n * math.tan(phi)), 1, delta=1e-3)
        self.assertEqual(contacts.field["joint_names"], ["interface"])
        self.assertTrue((contacts.cells["joint"] == 0).all())

    def test_standing_block_contacts_are_locked(self):
        # phi = 40.1 deg > 40 deg (case A3): the block stands on locked contacts, at every frame.
        for _, path in series(f"{self.out}/stand/vtk/contacts.pvd"):
            contacts = Grid(path)
            self.assertGreater(contacts.count(), 0)
            self.assertTrue((contacts.cells["state"] == LOCKED).all(), (path, contacts.cells["state"]))

    def test_toppling_block_rotation_moves_its_corner(self):
        # A rigid block: its top corner p moves by u_c + (R(theta) - I)(p0 - c0), u_c and theta
        # the block's displacement and rotation in the file; that must be history.csv's "top"
        # monitor to its 12 printed digits (two units of the last, as above).
        case = load_case("toppling_block.json")
        blocks = self.final("topple", "blocks")
        b = blocks.field["block_names"].index("block")
        u, theta = blocks.cells["displacement"][b], blocks.cells["rotation"][b]
        self.assertGreater(theta, 0.03)  # it topples counter-clockwise, downslope (-x)
        c0 = rectangle_centre(case["blocks"][b]["vertices"])
        top = next(m for m in case["monitors"] if m["id"] == "top")
        dx, dy = top["point"][0] - c0[0], top["point"][1] - c0[1]
        moved = (u[0] + (math.cos(theta) - 1) * dx - math.sin(theta) * dy,
                 u[1] + math.sin(theta) * dx + (math.cos(theta) - 1) * dy)
        row = last_row(f"{self.out}/topple/history.csv")
        for k, axis in enumerate("xy"):
            want = float(row["top_u" + axis])
            self.assertLess(abs(moved[k] - want), 2 * printed(want), axis)
        # Rigid blocks have no strain unknowns: their stress stays 0 (docs/case-format.md).
        self.assertTrue((blocks.cells["stress"] == 0).all())
        # It pivots on its toe (phi = 40 deg > 30 deg, A6): the contacts left are locked ones of
        # the block's toe vertex (case vertex 0, the downslope corner) on the ramp.
        contacts = self.final("topple", "contacts")
        self.assertGreater(contacts.count(), 0)
        self.assertTrue((contacts.cells["state"] == LOCKED).all(), contacts.cells["state"])
        toe = case["blocks"][b]["vertices"][0]
        points = vtk_to_numpy(contacts.grid.GetPoints().GetData())
        for c in range(contacts.count()):
            start = points[2 * c]
            self.assertLess(math.dist(start[:2], (toe[0] + float(row["toe_ux"]), toe[1] + float(row["toe_uy"]))), 1e-6)

    def test_water_table_is_the_phreatic_line(self):
        case = load_case("planar_failure_water.json")
        line = case["water"]["phreatic_line"]

        def head(x):  # linear between the line's points, flat beyond its ends (docs/case-format.md)
            if x <= line[0][0]:
                return line[0][1]
            if x >= line[-1][0]:
                return line[-1][1]
            for (x0, y0), (x1, y1) in zip(line, line[1:]):
                if x0 <= x <= x1:
                    return y0 + (y1 - y0) * (x - x0) / (x1 - x0)

        water = self.final("water", "water")
        self.assertEqual(water.count(), 1)
        self.assertEqual(water.types(), {VTK_POLY_LINE})
        points = vtk_to_numpy(water.grid.GetPoints().GetData())
        for x, y, z in points:
            self.assertAlmostEqual(y, head(x), delta=1e-12)
            self.assertEqual(z, 0)
        blocks = vtk_to_numpy(self.final("water", "blocks").grid.GetPoints().GetData())
        self.assertAlmostEqual(points[0][0], blocks[:, 0].min(), delta=1e-12)  # across the blocks' extent
        self.assertAlmostEqual(points[-1][0], blocks[:, 0].max(), delta=1e-12)

    def test_supports_are_lines_from_head_to_end_with_the_history_force(self):
        case = load_case("goodman_bray_toppling_anchor.json")
        support = case["supports"][0]
        self.assertFalse(os.path.exists(f"{self.out}/slide/vtk/supports.pvd"))  # no supports: no series
        supports = self.final("anchor", "supports")
        self.assertEqual(supports.count(), 1)
        self.assertEqual(supports.types(), {VTK_LINE})
        self.assertEqual(supports.field["support_names"], [support["id"]])
        self.assertEqual(supports.field["state_names"], ["elastic", "yielded", "slack", "broken"])
        row = last_row(f"{self.out}/anchor/history.csv")
        sid = support["id"]
        # history.csv prints 12 significant digits
        self.assertAlmostEqual(supports.cells["force"][0], float(row[f"{sid}_force"]),
                               delta=1e-11 * abs(float(row[f"{sid}_force"])))
        self.assertAlmostEqual(supports.cells["elongation"][0], float(row[f"{sid}_elongation"]), delta=1e-15)
        self.assertEqual(supports.cells["state"][0], 0)  # a constant-force anchor stays elastic
        # The line runs from the head's current point to the end (in the fixed rock: unmoved).
        points = vtk_to_numpy(supports.grid.GetPoints().GetData())
        self.assertAlmostEqual(points[1][0], support["end"][0], delta=1e-9)
        self.assertAlmostEqual(points[1][1], support["end"][1], delta=1e-9)
        self.assertLess(math.dist(points[0][:2], support["head"]), 0.01)


class SearchSeries(unittest.TestCase):
    def test_every_trial_final_state_at_its_value(self):
        with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as pictures:
            result = subprocess.run([DDASLOPE, "fos", case_path("stable_block_40deg.json"), "--json", "--vtk", out,
                                     "--out", pictures], check=True, capture_output=True, text=True)
            report = json.loads(result.stdout)
            frames = series(f"{out}/blocks.pvd")
            # One frame per factor tried, in increasing order: a review's re-run at a factor (listed
            # after the first run there) replaces that factor's frame, as its verdict replaces the
            # first one's.
            factors = sorted({t["factor"] for t in report["trials"]})
            self.assertEqual(report["forward_runs"], len(report["trials"]))
            self.assertEqual(report["forward_runs"] - len(factors), report["review"]["reruns"])
            self.assertEqual([t for t, _ in frames], factors)
            verdicts = {t["factor"]: t for t in report["trials"]}  # the last listed at a factor is in force
            for factor, path in frames:
                blocks = Grid(path)
                self.assertEqual(blocks.field["trial_value"], [factor])
                self.assertEqual(blocks.field["stable"], [1 if verdicts[factor]["stable"] else 0])
                self.assertEqual(blocks.field["verdict"], [verdicts[factor]["rule"]])
                self.assertEqual(blocks.field["simulated_time"], [verdicts[factor]["time_s"]])
            # The bracket's ends (F = 1.0031: the block holds at phi/F = 40.1 deg / F down to
            # 40 deg): on the stable end the contacts are locked, on the failing end they slide.
            stable_end, failing_end = report["bracket"]
            for factor, state in ((stable_end, LOCKED), (failing_end, SLIDING)):
                path = dict(series(f"{out}/contacts.pvd"))[factor]
                self.assertTrue((Grid(path).cells["state"] == state).all(), (factor, Grid(path).cells["state"]))

    def test_no_frame_for_a_run_the_search_did_not_take(self):
        # Three threads on the stepped slope: narrowing rounds whose first value passes the
        # failure displacement, the values beyond it not needed. Only the trials taken have frames.
        with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as pictures:
            result = subprocess.run([DDASLOPE, "fos", case_path("stepped_toppling.json"), "--json", "--threads", "3",
                                     "--vtk", out, "--out", pictures], check=True, capture_output=True, text=True)
            report = json.loads(result.stdout)
            self.assertEqual([t for t, _ in series(f"{out}/blocks.pvd")], sorted({t["factor"] for t in report["trials"]}))
            self.assertEqual(len(glob.glob(f"{out}/blocks_*.vtu")), len({t["factor"] for t in report["trials"]}))

    def test_curve_and_sweep_refuse_vtk(self):
        for args in (["critical", case_path("planar_failure.json"), "--joint", "sliding_plane", "--curve", "10:40:3"],
                     ["fos", case_path("planar_failure.json"), "--sweep", "water.level=0:1:2"]):
            with tempfile.TemporaryDirectory() as out:
                code = subprocess.run([DDASLOPE] + args + ["--vtk", out], capture_output=True).returncode
                self.assertEqual(code, 2, args)  # bad input


if __name__ == "__main__":
    unittest.main(verbosity=2)
