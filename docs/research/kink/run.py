#!/usr/bin/env python3
"""Driver for docs/research/kink-blocks.md: runs ddaslope critical / block_equilibrium one at a time,
appends one JSON line per measurement to results.jsonl. Usage: run.py chair|vajont|jiuf|slab"""
import json, subprocess, sys, time, os, shlex
# The binary and the checkout it runs in: DDASLOPE (default build/ddaslope) and the repository root.
MAIN = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
DDA = os.environ.get("DDASLOPE", os.path.join(MAIN, "build", "ddaslope"))
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results.jsonl")
PY = "/usr/bin/python3"

def log(rec):
    with open(OUT, "a") as f:
        f.write(json.dumps(rec) + "\n")
    print(json.dumps(rec), flush=True)

def run(cmd):
    t = time.time()
    p = subprocess.run(cmd, cwd=MAIN, capture_output=True, text=True)
    return p, time.time() - t

def critical(item, label, case, extra, sets):
    cmd = [DDA, "critical", case] + extra + ["--json", "--quiet", "--threads", "1"]
    for s in sets:
        cmd += ["--set", s]
    p, dt = run(cmd)
    try:
        d = json.loads(p.stdout)
        rec = dict(item=item, label=label, kind="critical", critical=d["critical"], found=d["found"],
                   bracket=d["bracket"], runs=d["forward_runs"], review=d.get("review"), wall=round(dt, 1),
                   rules=[(t.get("cohesion_pa", t.get("friction_deg")), t["stable"], t["rule"]) for t in d.get("trials", [])])
    except Exception as e:
        rec = dict(item=item, label=label, kind="critical", error=str(e), stderr=p.stderr[-2000:], rc=p.returncode)
    rec["cmd"] = " ".join(shlex.quote(c) for c in cmd).replace(DDA, "$DDA")
    log(rec)

def bound(item, label, case, args):
    cmd = [PY, "scripts/block_equilibrium.py", case] + args + ["--ddaslope", DDA, "--json"]
    p, dt = run(cmd)
    rec = dict(item=item, label=label, kind="bound", wall=round(dt, 1), rc=p.returncode)
    try:
        rec["result"] = json.loads(p.stdout)
    except Exception:
        rec["stdout"] = p.stdout[-1500:]; rec["stderr"] = p.stderr[-1500:]
    rec["cmd"] = " ".join(shlex.quote(c) for c in cmd).replace(DDA, "$DDA")
    log(rec)

def variant(src, name, mutate):
    c = json.load(open(os.path.join(MAIN, src)))
    mutate(c)
    c.pop("expected", None)
    path = os.path.join(os.path.dirname(OUT), name)
    # keep relative file references working (e.g. seismic records): absolutise nothing; write beside src instead
    json.dump(c, open(path, "w"), indent=1)
    return path

W0 = {"chair": 575.0, "vajont": 870.0, "jiuf": 1550.0}
KS = [2.5e-3, 5e-3, 1e-2]

what = sys.argv[1]
if what == "chair":
    case = "cases/chair_slide.json"
    widths = [0.0] + [k * W0["chair"] for k in KS] + [3.0]
    for off in [0.0, 10.0, 25.0, 40.0]:
        ox = 500.0 - off
        for w in widths:
            sets = [f"section.joint_sets[0].origin[0]={ox}", f"section.kink_block_width={w}"]
            critical("chair", dict(offset=off, w=w), case,
                     ["--joint", "sliding_surface", "--solve", "cohesion", "--friction", "18"], sets)
elif what == "chair_bounds":
    for off in [0.0, 10.0, 25.0, 40.0]:
        def m(c, off=off):
            c["section"]["joint_sets"][0]["origin"][0] = 500.0 - off
        path = variant("cases/chair_slide.json", f"chair_off{off:g}.json", m)
        for w in [0.0] + [k * W0["chair"] for k in KS] + [3.0]:
            bound("chair", dict(offset=off, w=w), path, ["--joint", "sliding_surface", "--friction", "18", "--kink-block-width", str(w)])
        p, dt = run([PY, "scripts/chair_slide.py", "le", "--case", path, "--friction", "18"])
        log(dict(item="chair", label=dict(offset=off), kind="le", stdout=p.stdout, stderr=p.stderr[-800:],
                 cmd=f"/usr/bin/python3 scripts/chair_slide.py le --case {path} --friction 18"))
elif what == "vajont":
    case = "cases/vajont.json"
    for w in sys.argv[2:] and [float(x) for x in sys.argv[2:]] or ([0.0] + [k * W0["vajont"] for k in KS] + [10.0]):
        critical("vajont", dict(w=w), case, ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0"],
                 [f"section.kink_block_width={w}"])
elif what == "vajont_bounds":
    for w in [float(x) for x in sys.argv[2:]]:
        bound("vajont", dict(w=w), "cases/vajont.json", ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0", "--kink-block-width", str(w)])
elif what == "jiuf":
    case = "cases/jiufengershan.json"
    for w in [0.0] + [k * W0["jiuf"] for k in KS]:
        critical("jiuf", dict(w=w), case, ["--joint", "bedding", "--solve", "friction", "--cohesion", "0"],
                 ["seismic.record.scale=0", f"section.kink_block_width={w}"])
elif what == "vajont_thick":
    path = os.path.join(os.path.dirname(OUT), "vajont_thick5.json")
    critical("vajont", dict(w="5% thickness per kink (9.19 m at 650, 11.04 m at 931.6), explicit joints"), path,
             ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0"], [])
    bound("vajont", dict(w="5% thickness per kink"), path, ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0"])
elif what == "slab":
    case = "cases/bilinear_slab.json"  # as drawn: the study predates moving the joint off the bend
    for w in [float(x) for x in sys.argv[2:]]:
        for sub in (["check"], ["cut", "--out", os.path.join(os.path.dirname(OUT), f"slab_cut_{w:g}")]):
            cmd = [DDA] + sub[:1] + [case] + sub[1:] + ["--set", f"section.kink_block_width={w}", "--set", "analysis.joint_end_offset=0"]
            p, dt = run(cmd)
            log(dict(item="slab", label=dict(w=w), kind=sub[0], stdout=p.stdout[-3000:], stderr=p.stderr[-1500:],
                     cmd=" ".join(cmd).replace(DDA, "$DDA")))
        cmd = [DDA, "fos", case, "--json", "--quiet", "--threads", "1", "--set", f"section.kink_block_width={w}",
               "--set", "analysis.joint_end_offset=0"]
        p, dt = run(cmd)
        try:
            d = json.loads(p.stdout); rec = dict(fos=d.get("critical", d.get("fos")), runs=d.get("forward_runs"), review=d.get("review"), found=d.get("found"))
        except Exception as e:
            rec = dict(error=str(e), stdout=p.stdout[-800:], stderr=p.stderr[-800:])
        log(dict(item="slab", label=dict(w=w), kind="fos", wall=round(dt, 1), cmd=" ".join(cmd).replace(DDA, "$DDA"), **rec))
        bound("slab", dict(w=w), case, ["--solve", "fos", "--kink-block-width", str(w)])
elif what == "jiuf_more":
    critical("jiuf", dict(w=3.23, note="5% of vertical thickness 64.7 m at the kink"), "cases/jiufengershan.json",
             ["--joint", "bedding", "--solve", "friction", "--cohesion", "0"], ["seismic.record.scale=0", "section.kink_block_width=3.23"])
    for w in [0.0, 3.875]:
        bound("jiuf", dict(w=w, without_corners="all"), os.path.join(os.path.dirname(OUT), "jiuf_static.json"),
              ["--joint", "bedding", "--solve", "friction", "--cohesion", "0", "--kink-block-width", str(w), "--without-corners"])
elif what == "vajont_offsets":
    for off in [10.0, 25.0, 40.0]:
        for w in [0.0, 8.7, 10.0, 4.35]:
            sets = [f"section.joint_sets[0].origin[0]={650.0 - off}", f"section.kink_block_width={w}"]
            critical("vajont", dict(offset=off, w=w), "cases/vajont.json",
                     ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0"], sets)
            def m(c, off=off):
                c["section"]["joint_sets"][0]["origin"][0] = 650.0 - off
            path = variant("cases/vajont.json", f"vajont_off{off:g}.json", m)
            bound("vajont", dict(offset=off, w=w), path, ["--joint", "sliding_surface", "--solve", "friction", "--cohesion", "0", "--kink-block-width", str(w)])
elif what == "bend":
    path = os.path.join(os.path.dirname(OUT), "bend_slide.json")
    for off in [0.0, 25.0, 40.0]:
        for w in [0.0, 2.5]:
            sets = [f"section.joint_sets[0].origin[0]={600.0 - off}", f"section.kink_block_width={w}"]
            critical("bend", dict(offset=off, w=w), path, ["--joint", "sliding_surface", "--solve", "cohesion", "--friction", "18"], sets)
        def m(c, off=off):
            c["section"]["joint_sets"][0]["origin"][0] = 600.0 - off
        vpath = variant(os.path.relpath(path, MAIN), f"bend_off{off:g}.json", m)
        for w in [0.0, 2.5]:
            bound("bend", dict(offset=off, w=w), vpath, ["--joint", "sliding_surface", "--friction", "18", "--kink-block-width", str(w)])
        bound("bend", dict(offset=off, w="slices"), vpath, ["--joint", "sliding_surface", "--friction", "18", "--kink-block-width", "0", "--without-corners"])
