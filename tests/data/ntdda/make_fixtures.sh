#!/bin/sh
# The ntdda fixtures of tests/test_ntdda_model.cpp, written by the project's own scripts
# (../shared/ntdda, the side-by-side with ntdda). Rerun from this folder when they change:
#   sh make_fixtures.sh /work/shared/ntdda
# benches*.geo and benches*.ana are written by hand: our own model in ntdda's DDAML and text
# forms (ntdda's example models carry no licence, so none is copied here).
set -e
S=${1:-../../../../shared/ntdda}
python3 "$S/make_wall.py" 3 > wall3.json
# --penalty: the case's own, ddaslope's default 40 E (json2ntdda's own default is 10 E).
python3 "$S/json2ntdda.py" wall3.json wall3 --penalty 4e11
# The same wall with a second material (the top row) and a second joint (between two bricks of
# the bottom row), to exercise material lines and joint types.
python3 - <<'PY'
import json
c = json.load(open("wall3.json"))
c["materials"]["soft"] = {"density": 2000, "young_modulus": 5e9, "poisson_ratio": 0.3}
c["joints"]["weak"] = {"friction_angle": 20, "cohesion": 1000, "tensile_strength": 500}
for b in c["blocks"]:
    if b["id"].startswith("r2"):
        b["material"] = "soft"
c["joint_pairs"] = [{"blocks": ["r0b0", "r0b1"], "joint": "weak"}]
json.dump(c, open("wall3_mixed.json", "w"))
PY
python3 "$S/json2ntdda.py" wall3_mixed.json wall3_mixed --penalty 4e11
