#!/usr/bin/env python3
"""Checks scripts/vajont_limit_equilibrium.py, chair_slide.py and spencer.py against closed forms and a
published example (run by ctest)."""
import json, math, os, subprocess, sys, tempfile, unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
import chair_slide  # noqa: E402
import spencer  # noqa: E402
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



def two_wedge_case(toe_x):
    """A 30 deg seat 100 m long onto a flat one ending at toe_x, the ground level with the crown:
    two wedges, cut at the kink (density 2500, joints 40 deg)."""
    drop = 100 * math.tan(math.radians(30))
    return {"materials": {"rock": {"density": 2500}}, "joints": {"j": {"friction_angle": 40}},
            "default_joint": "j",
            "section": {"ground": [[0, drop], [toe_x, drop], [toe_x, 0]],
                        "sliding_surface": [[0, drop], [100, 0], [toe_x, 0]]}}

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
        self.assertAlmostEqual(critical_friction(two_wedge_case(150), "--delta", "0"), 15, places=6)


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
        slices = section_slices(two_wedge_case(150))
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
        slices = section_slices(two_wedge_case(160))
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



class SpencerMorgensternPrice(unittest.TestCase):
    """scripts/spencer.py: Spencer's method and Morgenstern-Price (half-sine f), force and moment
    equilibrium of vertical slices (GLE formulation, Fredlund & Krahn 1977)."""
    PHI = 18.0

    def assertRelative(self, got, want, rel=1e-9):
        self.assertLessEqual(abs(got - want), rel * abs(want), f"{got} vs {want}")

    @staticmethod
    def plane_closed_form(slices, c, tan_phi):
        # Closed form (planar failure, Hoek & Bray): on one plane the normal and shear resultants
        # of the whole mass are W cos(b) and W sin(b), however the interfaces share them out.
        w, length, b = sum(s.w for s in slices), sum(s.length for s in slices), slices[0].beta
        return (c * length + w * math.cos(b) * tan_phi) / (w * math.sin(b))

    def test_single_planar_slice_closed_form(self):
        # Closed form: one block on a plane, F = (c L + W cos(b) tan(phi)) / (W sin(b)). A
        # parallelogram (ground parallel to the base, vertical sides), so its weight acts over its
        # base midpoint, where N and S act: moment equilibrium holds for every lambda, lambda is
        # irrelevant (solve returns 0), and F_f(lambda) is the closed form for every lambda.
        top = 100 * math.tan(math.radians(30))
        for level in (None, 1000):  # dry, and fully submerged (effective weight)
            slices = spencer.polyline_slices([[0, top + 20], [100, 20]], [[0, top], [100, 0]], [0, 100],
                                             2500 * 9.81, level)
            self.assertAlmostEqual(slices[0].xw, 50, places=9)
            for c in (0.0, 50e3):
                want = self.plane_closed_form(slices, c, math.tan(math.radians(self.PHI)))
                for method in spencer.METHODS:
                    F, second = spencer.factor_of_safety(slices, c, math.tan(math.radians(self.PHI)), method)
                    self.assertRelative(F, want)
                    self.assertEqual(second, 0.0)
                    f = spencer.interslice_function(slices, method)
                    for lam in (-0.5, 0.3, 1.0):
                        self.assertRelative(spencer.force_fos(slices, c, math.tan(math.radians(self.PHI)),
                                                              lam, f), want)

    def test_single_triangular_wedge_has_no_moment_equilibrium(self):
        # A limitation, pinned: one triangular wedge's weight acts 2/3 of the way along it, not over
        # its base midpoint, where the method puts N and S, and with no interfaces nothing else can
        # balance the couple. Force equilibrium alone gives the closed form; solve finds no lambda.
        # The same for several slices on one plane without cohesion: at F_f = tan(phi) / tan(b)
        # every base reaction is vertical, so E = 0 at every interface whatever lambda, and each
        # slice is left with its own couple.
        drop = 100 * math.tan(math.radians(30))
        slices = spencer.polyline_slices([[0, drop], [100, drop], [100, 0]], [[0, drop], [100, 0]], [0, 100],
                                         2500 * 9.81)
        tan_phi = math.tan(math.radians(self.PHI))
        f = spencer.interslice_function(slices, "spencer")
        self.assertRelative(spencer.force_fos(slices, 50e3, tan_phi, 0.2, f),
                            self.plane_closed_form(slices, 50e3, tan_phi))
        with self.assertRaises(ValueError):
            spencer.solve(slices, 50e3, tan_phi)
        slices = spencer.case_slices(planar_case(30))
        f = spencer.interslice_function(slices, "spencer")
        for lam in (0.0, 0.5):
            F = spencer.force_fos(slices, 0.0, tan_phi, lam, f)
            self.assertRelative(F, tan_phi / math.tan(math.radians(30)))
            self.assertTrue(all(abs(e) < 1e-6 for e in spencer.march(slices, 0.0, tan_phi, F, lam, f)[2]))
        with self.assertRaises(ValueError):
            spencer.solve(slices, 0.0, tan_phi)

    def test_slices_on_one_plane_closed_form(self):
        # Closed form (as above): several slices on one plane, whatever the interslice forces (any
        # lambda: internal forces cancel in the force equilibrium of the whole). Dry, and partly
        # submerged (each slice's effective weight; one dip, so the closed form takes their sum).
        # With cohesion: without, there is no moment equilibrium (the test above).
        tan_phi = math.tan(math.radians(self.PHI))
        for level in (None, 20):
            slices = spencer.case_slices(planar_case(30, level))
            self.assertEqual(len(slices), 5)
            for c in (20e3, 50e3):
                want = self.plane_closed_form(slices, c, tan_phi)
                for method in spencer.METHODS:
                    r = spencer.solve(slices, c, tan_phi, method)
                    self.assertRelative(r["F"], want)
                    self.assertRelative(r["F_m"], want)
                    f = spencer.interslice_function(slices, method)
                    for lam in (-0.3, 0.0, 0.5):
                        self.assertRelative(spencer.force_fos(slices, c, tan_phi, lam, f), want)

    def test_fredlund_krahn_1977_case_1(self):
        # Published example: Fredlund & Krahn (1977), "Comparison of slope stability methods of
        # analysis", Can. Geotech. J. 14(3):429-439, example problem, case 1: a 2H:1V slope 40 ft
        # high, c' = 600 psf, phi' = 20 deg, gamma = 120 pcf, no water, slip circle centre
        # (120, 90) ft, radius 80 ft. Published: Spencer F = 2.073 (lambda 0.237), Morgenstern-Price
        # with constant f 2.076 (lambda 0.254); Bishop 2.080. Quoted from the table of published
        # results on the MacSlope verification page (macslope.com/verification/fredlund-example,
        # MacSlope itself: Spencer 2.076, lambda 0.261), the coordinates as in pybimstab's example
        # of the case (crest y = 60 ft for x <= 60, toe y = 20 ft from x = 140, the circle entering
        # at x = 45.838 and leaving at 158.726); the paper itself was not at hand. Circular, not
        # the non-circular example we wanted: case 2 (a weak layer) is non-circular, but its
        # layer's depth could not be confirmed from a source, so it is not used. 50 slices of equal
        # width, bases the chords of the circle; F converges from above with the number of slices
        # (2.0744 at 30, 2.0728 at 50, 2.0721 at 100), so 0.005 covers the discretisation and the
        # published programs' spread (2.073 to 2.076). lambda is not compared: the published values
        # spread by 10 % (0.237 to 0.261), ours is 0.258.
        cx, cy, radius = 120.0, 90.0, 80.0
        x0, x1 = cx - math.sqrt(radius ** 2 - 30 ** 2), cx + math.sqrt(radius ** 2 - 70 ** 2)
        self.assertAlmostEqual(x0, 45.838, places=3)
        self.assertAlmostEqual(x1, 158.726, places=2)  # 158.730: pybimstab rounds differently
        xs = [x0 + (x1 - x0) * i / 50 for i in range(51)]
        surface = [[x, cy - math.sqrt(radius ** 2 - (x - cx) ** 2)] for x in xs]
        slices = spencer.polyline_slices([[0, 60], [60, 60], [140, 20], [170, 20]], surface, xs, 120.0)
        tan_phi = math.tan(math.radians(20))
        F, theta = spencer.factor_of_safety(slices, 600.0, tan_phi, "spencer")
        self.assertLess(abs(F - 2.073), 0.005, F)
        self.assertGreater(theta, 0)
        # Moments about the circle's centre, as the paper took them: the same solution.
        F_c, theta_c = spencer.factor_of_safety(slices, 600.0, tan_phi, "spencer", point=(cx, cy))
        self.assertRelative(F_c, F)
        # The half-sine function (not published for this case) changes F by under 0.1 %.
        F_mp, _ = spencer.factor_of_safety(slices, 600.0, tan_phi, "morgenstern-price")
        self.assertLess(abs(F_mp - F), 1e-3 * F)
        print(f"\nFredlund & Krahn 1977 case 1 (published Spencer 2.073): Spencer F {F:.4f} "
              f"(theta {theta:.2f} deg, lambda {math.tan(math.radians(theta)):.3f}), "
              f"Morgenstern-Price (half-sine) F {F_mp:.4f}")

    def test_effective_weight_acts_at_the_combined_centroid(self):
        # Closed form (polygon centroids): the chair slide's toe slice (x 800-850) is a triangle cut
        # by the water level; its effective weight acts at (rho g A xA - gamma_w A_wet x_wet) / W'.
        # Areas and centroids by the shoelace formula on the polygon and on its part below the level.
        with open(chair_slide.CASE_PATH) as f:
            case = json.load(f)
        toe = spencer.case_slices(case)[-1]
        level = case["water"]["level"]
        poly = [(toe.x0, toe.yb0), (toe.x1, toe.yb1), (toe.x1, toe.yt1), (toe.x0, toe.yt0)]

        def clip_below(pts, y):
            out = []
            for (xa, ya), (xb, yb) in zip(pts, pts[1:] + pts[:1]):
                if ya <= y:
                    out.append((xa, ya))
                if (ya - y) * (yb - y) < 0:
                    out.append((xa + (xb - xa) * (y - ya) / (yb - ya), y))
            return out

        def area_centroid(pts):
            a = cx = 0.0
            for (xa, ya), (xb, yb) in zip(pts, pts[1:] + pts[:1]):
                cross = xa * yb - xb * ya
                a += cross / 2
                cx += (xa + xb) * cross / 6
            return a, cx / a

        (a, xa), (aw, xw) = area_centroid(poly), area_centroid(clip_below(poly, level))
        self.assertTrue(0 < aw < a)
        rho_g = 2500 * 9.81
        self.assertRelative(toe.w, rho_g * a - 9810 * aw)
        self.assertRelative(toe.xw, (rho_g * a * xa - 9810 * aw * xw) / (rho_g * a - 9810 * aw))

    def test_chair_slide_slices_match_the_multi_wedge_slices(self):
        with open(chair_slide.CASE_PATH) as f:
            case = json.load(f)
        for s, (w, beta, length) in zip(spencer.case_slices(case), section_slices(case)):
            self.assertRelative(s.w, w, 1e-12)
            self.assertAlmostEqual(s.beta, beta, places=12)
            self.assertAlmostEqual(s.length, length, places=9)


class ChairSlideSpencer(unittest.TestCase):
    """cases/chair_slide.json by Spencer and Morgenstern-Price, against the multi-wedge range."""

    @classmethod
    def setUpClass(cls):
        with open(chair_slide.CASE_PATH) as f:
            cls.case = json.load(f)
        cls.slices = spencer.case_slices(cls.case)
        cls.wedges = section_slices(cls.case)
        cls.tan_phi = math.tan(math.radians(cls.case["joints"]["sliding_surface"]["friction_angle"]))
        cls.c = {m: spencer.critical_cohesion(cls.slices, cls.tan_phi, m) for m in spencer.METHODS}

    def test_critical_cohesion_within_the_multi_wedge_range(self):
        # The rigorous value must lie between the multi-wedge values for interface friction 0 (the
        # weakest) and the internal joints' 40 deg (the strongest).
        hi = chair_slide.critical_cohesion(self.wedges, self.tan_phi, 0.0)
        lo = chair_slide.critical_cohesion(self.wedges, self.tan_phi, math.tan(math.radians(40)))
        (c_s, theta), (c_mp, lam) = self.c["spencer"], self.c["morgenstern-price"]
        print(f"\nchair slide, phi 18 deg: multi-wedge c {lo / 1e3:.2f} (delta 40) to {hi / 1e3:.2f} kPa "
              f"(delta 0); Spencer {c_s / 1e3:.2f} kPa (theta {theta:.2f} deg), Morgenstern-Price "
              f"{c_mp / 1e3:.2f} kPa (lambda {lam:.3f})")
        for c in (c_s, c_mp):
            self.assertTrue(lo < c < hi, c)
        # Spencer's force equilibrium is the multi-wedge method with tan(delta) = tan(theta) (no
        # interface is in tension at the solution, so the multi-wedge's no-tension clamp is idle).
        self.assertRelative(chair_slide.critical_cohesion(self.wedges, self.tan_phi, math.tan(math.radians(theta))),
                            c_s)
        r = spencer.solve(self.slices, c_s, self.tan_phi)
        self.assertTrue(all(e > 0 for e in r["E"][1:-1]))

    def assertRelative(self, got, want, rel=1e-9):
        self.assertLessEqual(abs(got - want), rel * abs(want), f"{got} vs {want}")

    def test_critical_cohesion_gives_factor_one_and_matches_bisection(self):
        for method in spencer.METHODS:
            c, second = self.c[method]
            F, second_f = spencer.factor_of_safety(self.slices, c, self.tan_phi, method)
            self.assertAlmostEqual(F, 1.0, places=9)
            self.assertAlmostEqual(second_f, second, places=6)
            lo, hi = 0.0, 2e5  # bisection on c of F(c) = 1
            for _ in range(50):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if spencer.factor_of_safety(self.slices, mid, self.tan_phi, method)[0] < 1 \
                    else (lo, mid)
            self.assertRelative((lo + hi) / 2, c, 1e-9)

    def test_independent_of_the_moment_point(self):
        # With force and moment equilibrium both satisfied, the moment about any point vanishes:
        # F, lambda and the critical cohesion must not depend on the point (above, beside, below,
        # far away), and F_m(lambda) about the point meets F_f there.
        c = self.c["spencer"][0]
        points = [None, (425, 1000), (0, 0), (850, 0), (-5000, 3000), (2000, -500), (1e4, 1e4)]
        for method in spencer.METHODS:
            ref = spencer.solve(self.slices, c, self.tan_phi, method)
            c_ref = self.c[method][0]
            for point in points:
                r = spencer.solve(self.slices, c, self.tan_phi, method, point)
                self.assertRelative(r["F"], ref["F"], 1e-6)
                self.assertAlmostEqual(r["lam"], ref["lam"], delta=1e-6)
                self.assertRelative(r["F_m"], r["F"], 1e-6)
                self.assertRelative(spencer.critical_cohesion(self.slices, self.tan_phi, method, point)[0],
                                    c_ref, 1e-6)

    def test_line_of_thrust_closes_at_the_toe(self):
        # Each slice's moment equilibrium about its base midpoint fixes the height of the
        # interslice resultant on its downslope side; the last slice must then balance with no
        # force beyond the toe (the whole mass is in moment equilibrium).
        for method in spencer.METHODS:
            r = spencer.solve(self.slices, self.c[method][0], self.tan_phi, method)
            self.assertLess(abs(r["thrust"][-1]), 1e-12 * spencer._moment_scale(self.slices))

    def test_critical_friction_without_cohesion(self):
        # At c = 0 only tan(phi) / F enters: phi_crit from one solve by scaling, checked at F = 1,
        # and within the multi-wedge range (vajont_limit_equilibrium.critical_friction).
        hi = vajont_limit_equilibrium.critical_friction(self.wedges, 0.0)
        lo = vajont_limit_equilibrium.critical_friction(self.wedges, math.tan(math.radians(40)))
        for method in spencer.METHODS:
            phi, _ = spencer.critical_friction(self.slices, 0.0, method)
            self.assertAlmostEqual(
                spencer.factor_of_safety(self.slices, 0.0, math.tan(math.radians(phi)), method)[0], 1.0, places=9)
            self.assertTrue(lo < phi < hi, phi)


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
