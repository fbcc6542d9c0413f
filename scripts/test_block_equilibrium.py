#!/usr/bin/env python3
"""Checks scripts/block_equilibrium.py (limit equilibrium of the blocks themselves) against closed
forms and an independent limit-equilibrium code (run by ctest; needs scipy, Debian python3-scipy)."""
import json, math, os, sys, unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, HERE)
import block_equilibrium as be  # noqa: E402
import chair_slide  # noqa: E402
from vajont_limit_equilibrium import section_slices  # noqa: E402

DDASLOPE = os.environ.get("DDASLOPE_CLI", os.path.join(ROOT, "build", "ddaslope"))


def model(case_name):
    return be.BlockModel(be.load_blocks(os.path.join(ROOT, "cases", case_name), DDASLOPE))


class BlockEquilibrium(unittest.TestCase):
    def test_block_on_an_incline_closed_form(self):
        # Closed form (benchmark B1, reference/benchmarks.md; Hoek & Bray's planar failure):
        # c_cr = W (sin a - cos a tan phi) / L for the A2 block on a 40 deg ramp at phi = 20 deg.
        m = model("cohesive_block_42kpa.json")
        block = next(b for b in m.blocks if not b.get("fixed"))
        area, _ = be.area_centroid([tuple(v) for v in block["vertices"]])
        v = block["vertices"]
        base = math.dist(v[0], v[1])
        a, phi = math.radians(40), math.radians(20)
        want = 2000 * 10 * area * (math.sin(a) - math.cos(a) * math.tan(phi)) / base
        self.assertAlmostEqual(want / 1e3, 36.397, places=3)  # B1's quoted value
        self.assertLess(abs(be.critical_cohesion(m, "interface", 20) - want), 1e-9 * want)

    def test_a_single_joint_needs_no_default_joint(self):
        # As the case reader reads it: one joint is every pair's. A 4.5 x 10 m column on a 20 deg
        # plane with phi = 35 deg slides without toppling (b/h = 0.45 > tan 20 deg): F = tan 35 / tan 20.
        c, s = math.cos(math.radians(20)), math.sin(math.radians(20))
        col = [[0, 0], [4.5 * c, 4.5 * s], [4.5 * c - 10 * s, 4.5 * s + 10 * c], [-10 * s, 10 * c]]
        case = {"materials": {"rock": {"density": 2500, "young_modulus": 1e10, "poisson_ratio": 0.25}},
                "joints": {"plane": {"friction_angle": 35, "cohesion": 0}},
                "blocks": [{"id": "ground", "material": "rock", "fixed": True,
                            "vertices": [[-40 * c, -40 * s - 20], [40 * c, -40 * s - 20], [40 * c, 40 * s],
                                         [-40 * c, -40 * s]]},
                           {"id": "column", "material": "rock", "vertices": col}]}
        m = be.BlockModel(case)
        self.assertAlmostEqual(be.strength_reduction_factor(m), math.tan(math.radians(35)) / math.tan(math.radians(20)),
                               delta=1e-3)

    def test_block_on_an_incline_friction(self):
        # Closed form (A5): a block on a 30 deg plane without cohesion holds from phi = 30 deg;
        # the bisection narrows to 1e-3 deg.
        m = model("sliding_block_30deg.json")
        self.assertAlmostEqual(be.critical_friction(m, "interface", 0.0), 30, delta=1e-3)

    def test_strength_reduction_factor_of_a_block_on_an_incline(self):
        # Closed form (A2 block, c = 42 kPa, phi = 20 deg on 40 deg; B2 in reference/benchmarks.md):
        # F solves (c/F) L + W cos a tan(phi)/F = W sin a, so F = (c L + W cos a tan phi) / (W sin a),
        # 1.087 as the case's description says; the bisection narrows to 1e-6 of F.
        m = model("cohesive_block_42kpa.json")
        block = next(b for b in m.blocks if not b.get("fixed"))
        area, _ = be.area_centroid([tuple(v) for v in block["vertices"]])
        v = block["vertices"]
        w, a = 2000 * 10 * area, math.radians(40)
        want = (42e3 * math.dist(v[0], v[1]) + w * math.cos(a) * math.tan(math.radians(20))) / (w * math.sin(a))
        self.assertAlmostEqual(want, 1.087, places=3)
        self.assertAlmostEqual(be.strength_reduction_factor(m), want, delta=2e-6 * want)

    def test_yield_coefficient_of_a_block_on_an_incline(self):
        # Closed form (benchmarks.md §E): a block on alpha = 40 deg with phi = 40.1 deg stands a
        # horizontal coefficient toward the valley (-x here) up to tan(phi - alpha) = tan 0.1 deg;
        # the bisection narrows to 1e-6.
        m = model("stable_block_40deg.json")
        self.assertAlmostEqual(be.yield_coefficient(m, -1), math.tan(math.radians(0.1)), delta=2e-6)

    def test_chair_without_its_corner_contacts_is_the_multi_wedge_method(self):
        # Independent code: with only edge-to-edge interfaces (no block corner carrying a point
        # force) the blocks of the chair slide are the vertical slices of the multi-wedge method
        # with the joints' 40 deg on the interfaces (scripts/chair_slide.py, Sarma-type force
        # equilibrium); the least cohesion must be the same, to round-off.
        case = json.load(open(os.path.join(ROOT, "cases", "chair_slide.json")))
        wedges = chair_slide.critical_cohesion(section_slices(case), math.tan(math.radians(18)),
                                               math.tan(math.radians(40)))
        m = model("chair_slide.json")
        m.contacts = [c for c in m.contacts if c[4] > 0]
        self.assertLess(abs(be.critical_cohesion(m, "sliding_surface", 18) - wedges), 1e-9 * wedges)

    def test_chair_corner_at_the_kink_is_a_point_contact(self):
        # Geometry: the (kink) block above the kink touches the 8 deg segment only at its corner, and
        # the blocks' contacts are the 73 that ddaslope finds at t = 0 (`ddaslope check`): 70
        # interface ends and 3 corners (the kink's two and the toe's).
        m = model("chair_slide.json")
        self.assertEqual(len(m.contacts), 73)
        corners = sorted((m.blocks[c[0]]["id"], round(c[2][0], 3)) for c in m.contacts if c[4] == 0)
        self.assertEqual(corners, [("slide_11", 500.0), ("slide_12", 500.0), ("slide_18", 850.0)])


if __name__ == "__main__":
    unittest.main()
