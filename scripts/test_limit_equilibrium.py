#!/usr/bin/env python3
"""Checks scripts/vajont_limit_equilibrium.py against closed forms (run by ctest)."""
import json, math, os, subprocess, sys, tempfile, unittest

HERE = os.path.dirname(os.path.abspath(__file__))


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
