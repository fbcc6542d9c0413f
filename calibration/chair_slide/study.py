#!/usr/bin/env python3
"""Critical cohesion of a chair-shaped multi-block slide against the weakening distance, the block
size and the settings, beside limit equilibrium on the same slices (issue #14).

The slide is cases/chair_slide.json (scripts/chair_slide.py): a 30 deg bedding segment buttressed
by an 8 deg toe, vertical joints every 50 m, a 3 m kink block just above the kink. For block
sizes 40, 50 and 100 m (the joint set's spacing, always through the kink; narrower columns,
h/b > 1/tan 30°, topple) it prints the critical cohesion of the sliding surface at phi = 18 deg
from
- limit equilibrium on the same vertical slices: Spencer, Morgenstern-Price (half-sine) and the
  multi-wedge bounds (interfaces without friction, and at the joints' 40 deg), scripts/spencer.py;
- limit equilibrium of the same blocks (scripts/block_equilibrium.py): the least cohesion for which
  any set of contact forces holds every block, corners included; no DDA run of these blocks can
  stand below it (the static theorem);
- one block of the 30 deg segment standing alone (closed form);
- ddaslope `critical` with the default (softening, automatic distance) joint, with brittle bonds
  (weakening_distance 0, original DDA) and with set distances;
and, for the 50 m blocks, the kink block's width, where the joints meet the kink, and the
shipped case under other settings.

Run from the repository root after building (Debian's python3, which has python3-scipy):
    python3 calibration/chair_slide/study.py [--bin build/ddaslope] [--quick]
It takes about 3 minutes (--quick: the 50 m blocks only; --spacing 25 adds toppling columns).
"""
import argparse, copy, json, math, os, re, subprocess, sys, tempfile

sys.dont_write_bytecode = True
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import spencer  # noqa: E402
import block_equilibrium  # noqa: E402  (needs scipy: Debian python3-scipy)
from chair_slide import critical_cohesion as multi_wedge, single_block_cohesion  # noqa: E402
from vajont_limit_equilibrium import section_slices  # noqa: E402

PHI = 18.0
DISTANCES = [None, 0.0, 0.01, 0.03, 0.3, 1.0]  # None: the automatic default
KINK_OFFSETS = [0.0, 10.0, 25.0, 40.0]  # m up the slope from the kink to the nearest joint
KINK_WIDTHS = [0.0, 0.75, 1.5, 3.0, 6.25]  # m, kink block (0: none)
SETTINGS = [("vertex treatment", ["--contact-treatment", "vertex"]), ("accurate preset", ["--preset", "accurate"]),
            ("Δt 1 ms", ["--time-step", "0.001"]), ("1 thread", ["--threads", "1"]),
            ("fast preset", ["--preset", "fast"]), ("rigid blocks", ["--blocks", "rigid"])]


class Mixed(float):
    """A search whose verdicts still contradict (exit status 3): the answer lies in [lo, hi], the
    range where they are mixed (review.mixed_range); its value is the middle of that range."""

    def __new__(cls, lo, hi):
        v = float.__new__(cls, 0.5 * (lo + hi))
        v.lo, v.hi = lo, hi
        return v


def ddaslope_critical(binary, case_path, extra):
    """Critical cohesion (Pa) and forward runs from `ddaslope critical --json`."""
    cmd = [binary, "critical", case_path, "--joint", "sliding_surface", "--solve", "cohesion",
           "--friction", str(PHI), "--width", "300", "--json"] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 3):
        sys.exit(f"{' '.join(cmd)}: exit status {p.returncode}\n{p.stderr}")
    r = json.loads(p.stdout)
    if r["found"]:
        return r["critical"], r["forward_runs"]
    lo, hi = r["review"]["mixed_range"]
    if lo is None or hi is None:
        sys.exit(f"{' '.join(cmd)}: no critical cohesion: {r['message']}")
    return Mixed(lo, hi), r["forward_runs"]


def limit_equilibrium(case):
    tan_phi = math.tan(math.radians(PHI))
    slices = section_slices(case)
    return {
        "spencer": spencer.critical_cohesion(spencer.case_slices(case), tan_phi)[0],
        "morgenstern-price": spencer.critical_cohesion(spencer.case_slices(case), tan_phi, "morgenstern-price")[0],
        "wedges δ=0": multi_wedge(slices, tan_phi, 0.0),
        "wedges δ=40°": multi_wedge(slices, tan_phi, math.tan(math.radians(40))),
        "single block": max(single_block_cohesion(*s, tan_phi) for s in slices),
    }, len(slices)


def block_bound(binary, case_path):
    """Least cohesion (Pa) for which the case's own blocks can stand (scripts/block_equilibrium.py)."""
    model = block_equilibrium.BlockModel(block_equilibrium.load_blocks(case_path, binary))
    return block_equilibrium.critical_cohesion(model, "sliding_surface", PHI)


def variant(base, tmp, name, spacing=None, offset=0.0, kink=None):
    """The chair case with another joint spacing, the joint set shifted `offset` m up the slope, or
    another kink block width; written to tmp. Returns (case, path)."""
    case = copy.deepcopy(base)
    section = case["section"]
    if spacing is not None:
        section["joint_sets"][0]["spacing"] = spacing
    origin = section["joint_sets"][0]["origin"]
    section["joint_sets"][0]["origin"] = [origin[0] - offset, origin[1]]
    if kink is not None:
        section["kink_block_width"] = kink
    case.pop("expected", None)
    path = os.path.join(tmp, f"chair_{name}.json")
    json.dump(case, open(path, "w"))
    return case, path


def kink_blocks(binary, base, tmp, kpa):
    """50 m blocks with kink blocks of several widths (0: a 50 m block's corner on the kink)."""
    le, _ = limit_equilibrium(base)
    ref = le["wedges δ=40°"]
    print(f"\nThe kink block (50 m blocks; the slices' limit equilibrium with the joints' 40°: {kpa(ref)} kPa), "
          "critical c in kPa\n")
    print("| kink block width | same blocks (static bound) | ddaslope default | against the slices (δ = 40°) |\n"
          "|---|---|---|---|")
    for width in KINK_WIDTHS:
        _, path = variant(base, tmp, f"kink_{width}", kink=width)
        c, _ = ddaslope_critical(binary, path, [])
        label = "none (a 50 m block's corner on the kink)" if width == 0 else f"{width:g} m"
        print(f"| {label} | {kpa(block_bound(binary, path))} | {kpa(c)} | {100 * (c - ref) / ref:+.1f} % |", flush=True)


def kink_layouts(binary, base, tmp, kpa):
    """50 m blocks with the joint set shifted up the slope, so that a block spans the kink."""
    print("\nWhere the joints meet the kink (50 m blocks; offset: the nearest joint lies this far up the slope "
          "from the kink, 0 = through it), critical c in kPa\n")
    print("| offset | Spencer | wedges δ = 40° | kink block | same blocks (static bound) | ddaslope default |\n"
          "|---|---|---|---|---|---|")
    for offset in KINK_OFFSETS:
        for kink in (0.0, base["section"]["kink_block_width"]):
            case, path = variant(base, tmp, f"offset_{offset}_{kink}", offset=offset, kink=kink)
            le, _ = limit_equilibrium(case)
            c, _ = ddaslope_critical(binary, path, [])
            print(f"| {offset:g} m | {kpa(le['spencer'])} | {kpa(le['wedges δ=40°'])} | "
                  f"{'none' if kink == 0 else f'{kink:g} m'} | {kpa(block_bound(binary, path))} | {kpa(c)} |",
                  flush=True)


def planar_slide(binary, tmp, kpa):
    """The exact multi-block reference: cases/planar_multiblock_slide.json, with and without stage 3."""
    path = os.path.join(ROOT, "cases", "planar_multiblock_slide.json")
    case = json.load(open(path))
    alpha, tan_phi = math.radians(30), math.tan(math.radians(PHI))
    exact = 2500 * 9.81 * (0.5 * 50 * 400) * (math.sin(alpha) - math.cos(alpha) * tan_phi) / (400 / math.cos(alpha))
    unsettled = copy.deepcopy(case)
    unsettled["analysis"]["settle_dynamically"] = False
    unsettled_path = os.path.join(tmp, "planar_unsettled.json")
    json.dump(unsettled, open(unsettled_path, "w"))
    rows = [("default (start settled at rest)", path, []),
            ("start not settled (analysis.settle_dynamically false, before issue #14's fix)", unsettled_path, []),
            ("brittle (δw = 0)", path, ["--brittle-joints"])]
    rows += [(f"default, {label}", path, extra) for label, extra in SETTINGS]
    print(f"\nPlanar multi-block slide (cases/planar_multiblock_slide.json): exact limit equilibrium {kpa(exact)} kPa "
          f"(all blocks sliding on the plane); the same blocks' static bound {kpa(block_bound(binary, path))} kPa "
          "(the crown block's corner may carry load)\n")
    print("| ddaslope | critical c (kPa) | error |\n|---|---|---|")
    for label, p, extra in rows:
        c, _ = ddaslope_critical(binary, p, extra)
        print(f"| {label} | {kpa(c)} | {100 * (c - exact) / exact:+.1f} % |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "ddaslope"))
    ap.add_argument("--quick", action="store_true", help="50 m blocks only")
    ap.add_argument("--spacing", type=float, action="append",
                    help="block width (m), repeatable; default 40, 50, 100 (25 m columns topple: b/h < tan 30°)")
    a = ap.parse_args()
    base = json.load(open(os.path.join(ROOT, "cases", "chair_slide.json")))
    kpa = lambda v: (f"{v.lo / 1e3:.1f}–{v.hi / 1e3:.1f} (mixed)" if isinstance(v, Mixed) else f"{v / 1e3:.1f}")
    with tempfile.TemporaryDirectory() as tmp:
        print(f"Critical cohesion (kPa) of the chair slide's sliding surface at φ = {PHI:g}°\n")
        print("| blocks | Spencer | M–P | wedges δ = 0 / 40° | same blocks (static bound) | one block alone | "
              "ddaslope default | brittle (δw = 0) | " + " | ".join(f"δw = {d:g} m" for d in DISTANCES[2:]) + " |")
        print("|---" * (8 + len(DISTANCES) - 2) + "|")
        for spacing in ([50] if a.quick else (a.spacing or [40, 50, 100])):
            case, path = variant(base, tmp, f"spacing_{spacing}", spacing=spacing)
            le, n = limit_equilibrium(case)
            dda = []
            for d in DISTANCES:
                extra = [] if d is None else ["--set", f"joints.sliding_surface.weakening_distance={d}"]
                dda.append(ddaslope_critical(a.bin, path, extra)[0])
            print(f"| {n} × {spacing:g} m | {kpa(le['spencer'])} | {kpa(le['morgenstern-price'])} | "
                  f"{kpa(le['wedges δ=0'])} / {kpa(le['wedges δ=40°'])} | {kpa(block_bound(a.bin, path))} | "
                  f"{kpa(le['single block'])} | "
                  + " | ".join(kpa(v) for v in dda) + " |", flush=True)
        if not a.quick:
            kink_blocks(a.bin, base, tmp, kpa)
            kink_layouts(a.bin, base, tmp, kpa)
            planar_slide(a.bin, tmp, kpa)
        path = os.path.join(ROOT, "cases", "chair_slide.json")
        ref = limit_equilibrium(base)[0]["wedges δ=40°"]
        print(f"\nThe shipped case (50 m blocks, {base['section']['kink_block_width']:g} m kink block) under other "
              f"settings (ddaslope critical, kPa; same blocks' static bound {kpa(block_bound(a.bin, path))})\n")
        print("| setting | critical c | against the slices (δ = 40°) | forward runs |\n|---|---|---|---|")
        for label, extra in [("default", [])] + SETTINGS + [("brittle (δw = 0)", ["--brittle-joints"])]:
            c, runs = ddaslope_critical(a.bin, path, extra)
            print(f"| {label} | {kpa(c)} | {100 * (c - ref) / ref:+.1f} % | {runs} |", flush=True)
        print("\n(mixed): the search's verdicts still contradict within that range after its re-runs "
              "(exit status 3, review.mixed_range); its middle is compared.")


if __name__ == "__main__":
    main()
