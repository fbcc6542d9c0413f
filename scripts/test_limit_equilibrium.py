#!/usr/bin/env python3
"""Checks scripts/vajont_limit_equilibrium.py against closed forms (run by ctest)."""
import json, math, os, subprocess, sys, tempfile, unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
import chair_slide  # noqa: E402
from vajont_limit_equilibrium import section_slices, toe_thrust  # noqa: E402
import vajont_limit_equilibrium  # noqa: E402


def critical_friction(case, *args):
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(case, f)
    try:
        out = subprocess.run([sys.executable, os.path.join(HERE, "vajont_limit_equilibrium.py"), f.name, *args],
                             check=True, capture_output=True, text=True).stdout
    finally:
        os.remove(f.name)
    return float(out.split("critical friction")[1].split("deg")[0])


def planar_case(dip_deg, level=None):
    """A 100 m wide mass on one plane dipping dip_deg, under a horizontal ground surface."""
    import math
    drop = 100 * math.tan(math.radians(dip_deg))
    case = {"materials": {"rock": {"density": 2500}}, "joints": {"j": {"friction_angle": 40}}, "default_joint": "j",
            "section": {"ground": [[0, drop], [100, drop], [100, 0]], "sliding_surface": [[0, drop], [100, 0]],
                        "joint_sets": [{"angle": 90, "spacing": 20, "origin": [0, 0]}]}}
    if level is not None:
        case["water"] = {"level": level}
    return case


def toppling_factor(blocks, *args):
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump({"blocks": blocks}, f)
    try:
        out = subprocess.run([sys.executable, os.path.join(HERE, "toppling_limit_equilibrium.py"), f.name, *args],
                             check=True, capture_output=True, text=True).stdout
    finally:
        os.remove(f.name)
    return float(out.split("limit-equilibrium factor of safety:")[1].split()[0])


class LimitEquilibrium(unittest.TestCase):
    def test_dry_plane(self):
        # Closed form: a rigid mass on one plane with c = 0 slides when tan(phi) = tan(dip), whatever
        # the vertical interfaces carry (every slice sits on the same plane).
        for dip in (20, 35):
            self.assertAlmostEqual(critical_friction(planar_case(dip)), dip, places=6)

    def test_submerged_plane(self):
        # Closed form: full hydrostatic submergence (water on every face) is buoyancy, which scales
        # the base's normal and shear alike, so the critical friction is still the dip.
        self.assertAlmostEqual(critical_friction(planar_case(30, level=1000)), 30, places=6)

    def test_partly_submerged_plane(self):
        # Closed form: on a uniform plane each slice's buoyancy scales its own base forces alike,
        # so partial submergence leaves the critical friction at the dip too.
        self.assertAlmostEqual(critical_friction(planar_case(30, level=20)), 30, places=6)

    def test_two_equal_wedges_without_interface_friction(self):
        # Closed form (two-wedge method, delta = 0): W1 tan(b1 - phi) + W2 tan(b2 - phi) = 0. With
        # equal weights and a flat seat (b2 = 0), tan(b1 - phi) = tan(phi): phi = b1 / 2.
        import math
        drop = 100 * math.tan(math.radians(30))
        case = {"materials": {"rock": {"density": 2500}}, "joints": {"j": {"friction_angle": 40}},
                "default_joint": "j",
                "section": {"ground": [[0, drop], [150, drop], [150, 0]],
                            "sliding_surface": [[0, drop], [100, 0], [150, 0]]}}
        self.assertAlmostEqual(critical_friction(case, "--delta", "0"), 15, places=6)


class CohesiveWedges(unittest.TestCase):
    """toe_thrust with a cohesion on the slice bases (scripts/chair_slide.py le)."""
    PHI = 18.0

    def assertRelative(self, got, want, rel=1e-9):
        self.assertLessEqual(abs(got - want), rel * abs(want), f"{got} vs {want}")

    def test_single_planar_slice_closed_form(self):
        # Closed form (Hoek & Bray, Rock Slope Engineering, planar failure, no water, no crack; FS = 1):
        # c A + W cos(b) tan(phi) = W sin(b), so c = W (sin b - cos b tan phi) / L. One slice alone
        # has no interfaces, so delta must not matter.
        case = planar_case(30)
        del case["section"]["joint_sets"]  # one slice: the whole wedge
        (w, beta, length), = section_slices(case)
        self.assertRelative(w, 2500 * 9.81 * 100 * 100 * math.tan(math.radians(30)) / 2)  # triangle area
        tan_phi = math.tan(math.radians(self.PHI))
        want = w * (math.sin(beta) - math.cos(beta) * tan_phi) / length
        for delta in (0, 40):
            got = chair_slide.critical_cohesion([(w, beta, length)], tan_phi, math.tan(math.radians(delta)))
            self.assertRelative(got, want)

    def test_submerged_planar_slice_closed_form(self):
        # Closed form: fully submerged (water on every face) the slice's net water force is buoyancy,
        # so the planar-failure cohesion above holds with the effective weight (rho - rho_w) g A.
        case = planar_case(30, level=1000)
        del case["section"]["joint_sets"]
        (w, beta, length), = section_slices(case)
        area = 100 * 100 * math.tan(math.radians(30)) / 2
        w_eff = (2500 * 9.81 - 9810) * area
        self.assertRelative(w, w_eff)
        tan_phi = math.tan(math.radians(self.PHI))
        got = chair_slide.critical_cohesion([(w, beta, length)], tan_phi, 0.0)
        self.assertRelative(got, w_eff * (math.sin(beta) - math.cos(beta) * tan_phi) / length)

    def test_zero_cohesion_leaves_the_friction_results(self):
        # Closed form (two-wedge method, delta = 0, c = 0; test_two_equal_wedges_without_interface_
        # friction): equal weights on 30 deg and 0 deg seats are critical at phi = 15 deg. Through the
        # imported functions with the base lengths carried and c = 0 given explicitly, and the thrust
        # bit-identical with and without the cohesion argument.
        drop = 100 * math.tan(math.radians(30))
        case = {"materials": {"rock": {"density": 2500}}, "joints": {"j": {"friction_angle": 40}},
                "default_joint": "j",
                "section": {"ground": [[0, drop], [150, drop], [150, 0]],
                            "sliding_surface": [[0, drop], [100, 0], [150, 0]]}}
        slices = section_slices(case)
        phi = vajont_limit_equilibrium.critical_friction(slices, 0.0, cohesion=0.0)
        self.assertAlmostEqual(phi, 15, places=9)
        for tan_phi in (0.1, 0.3, 0.5):
            for tan_delta in (0.0, 0.8):
                self.assertEqual(toe_thrust(slices, tan_phi, tan_delta),
                                 toe_thrust([s[:2] for s in slices], tan_phi, tan_delta, 0.0))

    def test_two_wedges_with_cohesion_closed_form(self):
        # Closed form (two-wedge method, delta = 0: a horizontal interface force): the force polygon
        # of a wedge on a base dipping b, with friction phi and cohesion force c L on the base, gives
        # the horizontal thrust it passes on as W tan(b - phi) - c L cos(phi) / cos(b - phi). The
        # pair is critical when the thrusts sum to zero: c = sum W tan(b - phi) / sum L cos(phi) /
        # cos(b - phi).
        drop = 100 * math.tan(math.radians(30))
        case = {"materials": {"rock": {"density": 2500}}, "joints": {"j": {"friction_angle": 40}},
                "default_joint": "j",
                "section": {"ground": [[0, drop], [160, drop], [160, 0]],
                            "sliding_surface": [[0, drop], [100, 0], [160, 0]]}}
        slices = section_slices(case)
        phi = math.radians(10)  # the upper wedge drives and needs the lower one
        want = sum(w * math.tan(b - phi) for w, b, _ in slices) / \
            sum(length * math.cos(phi) / math.cos(b - phi) for _, b, length in slices)
        self.assertGreater(want, 0)
        self.assertRelative(chair_slide.critical_cohesion(slices, math.tan(phi), 0.0), want)


class ChairSlide(unittest.TestCase):
    """cases/chair_slide.json (scripts/chair_slide.py): the toe buttress."""

    def setUp(self):
        with open(chair_slide.CASE_PATH) as f:
            self.case = json.load(f)
        self.slices = section_slices(self.case)
        self.tan_phi = math.tan(math.radians(self.case["joints"]["sliding_surface"]["friction_angle"]))

    def test_single_block_on_the_30_degree_segment_closed_form(self):
        # Closed form (infinite slope, dry: the 30 deg blocks lie above the reservoir): a block of
        # vertical height h = t / cos(a) needs c = gamma h cos(a) (sin a - cos a tan phi).
        a, h = math.radians(30), 50 / math.cos(math.radians(30))
        want = 2500 * 9.81 * h * math.cos(a) * (math.sin(a) - math.cos(a) * self.tan_phi)
        got = max(chair_slide.single_block_cohesion(*s, self.tan_phi) for s in self.slices)
        self.assertLessEqual(abs(got - want), 1e-9 * want)

    def test_whole_slide_needs_less_than_half_the_single_block_cohesion(self):
        # Closed form (multi-wedge, delta = 0): as for two wedges, a run of slices whose interfaces
        # are all in compression at the limit is critical at c = sum W' tan(b - phi) / sum L cos(phi)
        # / cos(b - phi). The crown wedge alone needs less than that (its single-block value), so its
        # interface would be in tension and carries nothing (no-tension joints): the run is slices
        # 2 to the toe, all 30 deg slices driving, all slices of the flatter segment resisting.
        phi = math.atan(self.tan_phi)
        run = self.slices[1:]
        want = sum(w * math.tan(b - phi) for w, b, _ in run) / \
            sum(length * math.cos(phi) / math.cos(b - phi) for _, b, length in run)
        got = chair_slide.critical_cohesion(self.slices, self.tan_phi, 0.0)
        self.assertLessEqual(abs(got - want), 1e-9 * want)
        singles = [chair_slide.single_block_cohesion(*s, self.tan_phi) for s in self.slices]
        self.assertLess(singles[0], got)
        for (_, b, _), c in zip(self.slices[1:], singles[1:]):  # steep ones drive, flat ones resist
            self.assertTrue(c > got if b > phi else c < 0)
        # The point of the case: under half the single-block value, and under the case's own
        # cohesion (limit equilibrium has the slope hold); interface friction (delta = 40 deg, the
        # internal joints') only adds strength.
        self.assertLess(2 * got, max(singles))
        self.assertLess(got, self.case["joints"]["sliding_surface"]["cohesion"])
        tan_delta = math.tan(math.radians(40))
        self.assertLess(chair_slide.critical_cohesion(self.slices, self.tan_phi, tan_delta), got)


class GoodmanBray(unittest.TestCase):
    def test_squat_column_slides_at_the_plane_closed_form(self):
        # Closed form: a column too squat to topple (width 10 m, height 3 m) on a basal joint
        # dipping psi slides when tan(phi)/F = tan(psi): F = tan(phi) / tan(psi).
        import math
        psi, phi = 20.0, 30.0
        t = math.tan(math.radians(psi))
        o_up, o = (0.0, 0.0), (10 * math.cos(math.radians(psi)), -10 * math.sin(math.radians(psi)))
        column = {"id": "c", "vertices": [list(o_up), list(o), [o[0], o[1] + 3], [0.0, 3.0]]}
        base = {"id": "base", "fixed": True,
                "vertices": [[-5.0, 5 * t], [-5.0, -20.0], [20.0, -20.0], [20.0, -20 * t]]}
        got = toppling_factor([base, column], "--joint-angle", "90", "--phi", str(phi))
        self.assertAlmostEqual(got, math.tan(math.radians(phi)) / t, places=4)


class SteppedToppling(unittest.TestCase):
    """scripts/stepped_toppling.py against Hoek & Bray's worked example (Rock Slope Engineering,
    1981; Wyllie & Mah 2004, sec. 7.3): limiting equilibrium at phi = 38.15 deg, the top three
    columns stable, the three at the toe sliding, the rest toppling."""

    def run_fos(self, phi):
        out = subprocess.run([sys.executable, os.path.join(HERE, "stepped_toppling.py"), "fos", "--phi", str(phi)],
                             check=True, capture_output=True, text=True).stdout
        return out, float(out.split("limit-equilibrium factor of safety:")[1].split()[0])

    def test_published_limiting_friction_gives_factor_one(self):
        out, F = self.run_fos(38.15)
        self.assertAlmostEqual(F, 1.0, delta=0.002)  # 38.15 deg is quoted to 0.01 deg: 0.0005 in F
        modes = [line.split(",")[2] for line in out.splitlines()[1:17]]  # columns 16 down to 1
        self.assertEqual(modes[:3], ["stable"] * 3)
        self.assertEqual(modes[3:13], ["topples"] * 10)
        self.assertEqual(modes[13:15], ["slides"] * 2)

    def test_factor_scales_with_tan_phi_for_a_fixed_mechanism(self):
        # F is the reduction of tan(phi) that reaches the limit, so it is tan(phi)/tan(phi_crit).
        _, F = self.run_fos(40)
        self.assertAlmostEqual(F, math.tan(math.radians(40)) / math.tan(math.radians(38.13)), delta=0.002)


if __name__ == "__main__":
    unittest.main()
