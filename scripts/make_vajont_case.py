#!/usr/bin/env python3
"""Writes cases/vajont.json from ../shared/data/vajont/case.json (the Vajont 1963 section of Boon,
Houlsby & Utili's 2-D model, with reconstructed break points). Run: python3 scripts/make_vajont_case.py
[--datum 630] [--kink 650] [--kink-block-width 10]. Every number's provenance is in the shared data's README."""
import argparse, json, math, os

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "data", "vajont", "case.json")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--datum", type=float, default=630.0, help="m a.s.l. of y = 0 (reconstructed: 600-630)")
    ap.add_argument("--kink", type=float, default=650.0, help="x of the upper slip-surface kink x_b (560-700)")
    ap.add_argument("--reservoir", type=float, default=700.42, help="reservoir level, m a.s.l.")
    ap.add_argument("--spacing", type=float, default=50.0,
                    help="vertical joints every this many m (kinematic freedom); 0: only J1 and J2 at the kinks (3 blocks)")
    ap.add_argument("--kink-block-width", type=float, default=10.0,
                    help="section.kink_block_width: a vertical joint this many m up the slope of each concave kink of "
                         "the sliding surface, so that no wide block leans on its corner there (docs/vajont.md, "
                         "issue #14); wider than the 5 m failure displacement. 0: none")
    ap.add_argument("--keep-valley-steps", action="store_true",
                    help="keep the opposite bank's sub-metre vertical steps (walls to a sliding block)")
    ap.add_argument("--runout", type=float, default=None, metavar="PHI_RES",
                    help="write a run-out case instead: residual friction PHI_RES on the sliding surface, 45 s "
                         "(the quoted duration of the collapse)")
    ap.add_argument("--trigger", type=float, nargs=3, default=None, metavar=("PHI_PEAK", "PHI_RES", "DW"),
                    help="write a failure-to-run-out case instead: one sliding-surface law, peak friction PHI_PEAK "
                         "falling to PHI_RES over a slip of DW m, from the failure level to rest (60 s)")
    ap.add_argument("--anchor", type=float, nargs=2, default=None, metavar=("PHI", "FORCE"),
                    help="an ANCHORED variant: the sliding surface at PHI deg (the back-analysed trigger friction) "
                         "and a 200 m toe anchor holding FORCE N/m (sized with critical --solve support)")
    ap.add_argument("--out", default=os.path.join(HERE, "..", "cases", "vajont.json"))
    a = ap.parse_args()
    data = json.load(open(SHARED))
    cs = data["cross_section"]
    ground = [[p["x"], p["y"]] for p in cs["ground_surface"]]
    valley = [[p["x"], p["y"]] for p in cs["valley_floor_and_opposite_bank"]["points"]]
    if not a.keep_valley_steps:
        # The valley points are the upper envelope of Boon's five boundary blocks. Where two blocks
        # meet, the envelope has a 0.2-4 m vertical step. To a sliding rigid block the step at the
        # foot of the opposite bank is a wall, and it stopped every run-out there. The terrain it
        # stands for is a continuous slope, so each step becomes one point at its mean height.
        merged = []
        for x, y in valley:
            if merged and abs(merged[-1][0] - x) < 1e-9:
                merged[-1][1] = round((merged[-1][1] + y) / 2, 3)
            else:
                merged.append([x, y])
        valley = merged
    ground += valley
    dips = cs["sliding_surface"]["segment_dips_deg"]
    crown = [0.0, 566.2]
    back, middle = math.radians(dips["upper_back"]["value"]), math.radians(dips["middle"]["value"])
    kink = [a.kink, round(crown[1] - a.kink * math.tan(back), 3)]
    seat_x = round(kink[0] + kink[1] / math.tan(middle), 3)
    surface = [crown, kink, [seat_x, 0.0], [1215.0, 0.0]]
    rho = data["material"]["density_kg_m3"]["value"]
    # Vertical joints every `spacing` m through the upper kink. In a run-out, one closer than half a
    # spacing to the toe cuts off a sliver wedge (15 m wide at x = 1200 m with the 50 m spacing)
    # that the mass squeezes against the opposite bank and shoots off like a pip (docs/vajont.md),
    # so there the toe block keeps that strip. The static case keeps it: the critical friction
    # moves by 0.01 deg without it (18.025 against 18.016).
    toe_x = surface[-1][0]
    moving = a.runout is not None or a.trigger is not None  # a run-out: no sliver at the toe
    last = toe_x - a.spacing / 2 if moving else toe_x
    vertical_joints = [a.kink] if a.spacing <= 0 else sorted(
        round(a.kink + k * a.spacing, 3) for k in range(-int(a.kink // a.spacing), int((toe_x - a.kink) // a.spacing) + 1)
        if 0 < a.kink + k * a.spacing < last and abs(a.kink + k * a.spacing - seat_x) > 1e-6)
    case = {
        "description": (
            "Vajont (Vaiont) rockslide, 9 Oct 1963, section of Boon, Houlsby & Utili (2014) 2-D DEM model "
            "(BOON2D script, quoted planes); ground surface quoted, sliding-surface dips quoted (37.49, 13.5, 0 deg), "
            f"break points reconstructed (upper kink x_b = {a.kink:g} m chosen in 560-700 to match the quoted volume); "
            f"internal joints: vertical, every {a.spacing:g} m through the upper kink, plus J2 at the lower kink "
            "(reconstructed: rigid blocks need this kinematic freedom to follow the chair-shaped surface, see docs/vajont.md)"
            + (f"; kink blocks: a vertical joint {a.kink_block_width:g} m up the slope of each concave kink of the sliding "
               "surface (section.kink_block_width, reconstructed: a wide block whose lower corner sits on the kink leans on "
               "that corner, a buttress slices and a crushing rock mass do not have; wider than the 5 m failure "
               "displacement, see docs/vajont.md)" if a.kink_block_width > 0 else "") + ". "
            "Valley floor and opposite bank: the upper envelope of Boon's boundary blocks, with its vertical steps "
            "(0.3-4 m, where two blocks meet) replaced by one point at the mean height (reconstructed). "
            "Density 2395.5 kg/m3 quoted "
            "(BOON2D). Internal joints phi = 40 deg quoted (BOON2D rock friction); sliding surface c = 0 (Boon), phi to be "
            f"back-analysed. Reservoir {a.reservoir} m a.s.l. at failure (Doc. 76-bis p207), datum y = 0 at "
            f"{a.datum:g} m a.s.l. (reconstructed, 600-630). Young's modulus 10 GPa assumed (not in the sources). "
            "Source data and labels: ../shared/data/vajont (README, case.json). Regenerate: scripts/make_vajont_case.py"),
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": rho, "young_modulus": 10e9, "poisson_ratio": 0.25}},
        "joints": {"sliding_surface": {"friction_angle": 22.0, "cohesion": 0},
                   "internal": {"friction_angle": data["material"]["rock_joint_friction_deg"]["value_2D"], "cohesion": 0}},
        "default_joint": "internal",
        "section": {
            "ground": ground,
            "sliding_surface": surface,
            "base_depth": 100,
            "material": "rock",
            "sliding_joint": "sliding_surface",
            # A joint set where it covers the mass; explicit joints where the run-out drops one.
            "joints": [[[seat_x, 0.0], [seat_x, 100.0]]] + (
                [[[x, -1.0], [x, 700.0]] for x in vertical_joints] if moving or a.spacing <= 0 else []),
            "joint_sets": [{"angle": 90, "spacing": a.spacing, "origin": [a.kink, 0.0]}]
                          if not moving and a.spacing > 0 else [],
            # A thin block up the slope of each concave kink (issue #14): without it the block
            # there leans on its lower corner, and the back-analysed friction is that corner's.
            **({"kink_block_width": a.kink_block_width} if a.kink_block_width > 0 else {}),
        },
        "monitors": [{"id": "crown", "point": [400, 330]}, {"id": "toe", "point": [1100, 40]}],
        "water": {"level": round(a.reservoir - a.datum, 3)},
        # Verdict for a 1.2 km slide: before the stage-3 start stable runs moved up to ~0.7 m while
        # the mass settled, then came to rest; failing ones keep accelerating (docs/vajont.md).
        "analysis": {"duration": 20.0, "time_step": 0.01, "failure_displacement": 5.0},
        "expected": [{"monitor": "toe", "quantity": "displacement", "at_most": 0.1,
                      "source": "phi = 22 deg lies above the back-analysed critical friction (docs/vajont.md): the slope holds"}],
    }
    if a.runout is not None:
        # After failure the seam keeps a residual friction only; the collapse lasted under 45 s
        # (quoted, S8 p41). Observed: 300-400 m horizontal travel, 17-30 m/s (docs/vajont.md).
        case["description"] += (f" RUN-OUT variant: residual friction {a.runout:g} deg on the sliding surface "
                                 "(to be back-analysed from the observed 300-400 m horizontal travel and 17-30 m/s), "
                                 "45 s, reservoir held at its level (the wave is not modelled).")
        case["joints"]["sliding_surface"]["friction_angle"] = a.runout
        case["analysis"] = {"duration": 45.0, "time_step": 0.01}
        del case["expected"]
    if a.trigger is not None:
        peak, residual, distance = a.trigger
        # One law for the seam from trigger to deposit (issue #14): the peak friction at which the
        # slope fails at the failure level, softening over a slip to the residual friction of the
        # run-out. The distance is assumed: ring-shear tests bring clays to residual over some
        # hundreds of mm, and no Vajont value was retrieved (shared data README).
        case["description"] += (f" TRIGGER-TO-RUN-OUT variant: one sliding-surface law, peak friction {peak:g} deg "
                                 "(just below this layout's critical friction at the failure level, docs/vajont.md: F < 1, the slope fails) "
                                 f"softening to a residual {residual:g} deg (the run-out's back-analysed value) over "
                                 f"a slip of {distance:g} m (assumed), 60 s from the failure level to rest; reservoir "
                                 "held at its level (the wave is not modelled). Observed: 300-400 m horizontal travel, "
                                 "17-30 m/s, under 45 s.")
        case["joints"]["sliding_surface"].update(
            {"friction_angle": peak, "residual_friction_angle": residual, "weakening_distance": distance})
        # The strength-reduction verdict of a fit's F = 1 observation as for the static case.
        case["analysis"] = {"duration": 60.0, "time_step": 0.01, "failure_displacement": 5.0}
        del case["expected"]
    if a.anchor is not None:
        phi, force = a.anchor
        # The toe's face, 10 m inside it, towards the crown and 30 deg down through the seat into
        # the rock below: the anchor pulls the mass back where it moves out over the valley.
        head = [1100.0, 80.0]
        down = math.radians(30)
        end = [round(head[0] - 200 * math.cos(down), 3), round(head[1] - 200 * math.sin(down), 3)]
        case["description"] += (f" ANCHORED variant: the sliding surface at the back-analysed trigger friction "
                                 f"{phi:g} deg (F = 1 at the failure level, docs/vajont.md) and one 200 m anchor "
                                 "from the toe's face, 30 deg below the horizontal into the rock below the seat, "
                                 f"holding {force / 1e6:g} MN per metre of slope: the force that "
                                 "`ddaslope critical cases/vajont_anchor.json --solve support --support anchor "
                                 "--target-fos 1.3` finds for F = 1.3 (docs/supports.md). Hundreds of 1 MN anchors "
                                 "per metre: no support could have held Vajont.")
        case["joints"]["sliding_surface"]["friction_angle"] = phi
        # The head lies on the vertical joint between two slices: the one up the slope carries it.
        case["supports"] = [{"id": "anchor", "head": head, "head_block": "slide_25", "end": end, "pretension": force}]
        case["expected"] = [{"monitor": "toe", "quantity": "displacement", "at_most": 0.1,
                             "source": "F = 1.3 with the anchor: the slope holds"}]
    with open(a.out, "w") as f:
        json.dump(case, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
