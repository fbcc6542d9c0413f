#!/usr/bin/env python3
"""A fuzz campaign of the command line on mutated shipped cases (issue #44).

usage: scripts/fuzz_cli.py BUILD_DIR --minutes 30 [--seed 1] [--keep DIR]

Each round takes a shipped case (cases/*.json), mutates one or two of its values (a number
scaled by a power of ten, set to 0, negated or made huge; a key deleted; a value replaced by one
of another type; an array element repeated or dropped) and runs one of `check`, `run`, `fos` and
`critical` on it under a time limit (check 20 s, the others 75 s: past the minute, a long command
has said so). Every outcome must be one of the documented ones:

  exit 0 (done), 2 (refused: the file and the place named), 3 (no answer, said why),
  or a run stopped by the limit after it said on stderr that it is long work (a size statement,
  a progress line, or a warning that names why).

Counted as defects, and the mutated case kept in --keep: exit 1 (an internal error), a signal,
a run stopped by the limit without a word, or a nan/inf in any file written.
"""
import argparse
import copy
import glob
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

LIMITS = {"check": 20, "run": 75, "fos": 75, "critical": 75}
# What long work says on stderr before the limit: a size statement or progress (run, searches)
# or a warning about the cause.
SAID = re.compile(r"a long run:|bringing \d+ blocks to rest|t = .* / .* s|bracket:|narrow:|warning:|note:"
                  r"|^\s*(fos|critical) (working|\w+:)", re.MULTILINE)


def paths(doc, prefix=()):
    """Every (path, value) of the document."""
    yield prefix, doc
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            yield from paths(v, prefix + (i,))


def parent(doc, path):
    for p in path[:-1]:
        doc = doc[p]
    return doc


def mutate(doc, rng):
    candidates = [p for p, _ in paths(doc) if p and p[0] not in ("description",)]
    path = rng.choice(candidates)
    holder, key = parent(doc, path), path[-1]
    value = holder[key]
    kind = rng.random()
    if isinstance(value, (int, float)) and not isinstance(value, bool) and kind < 0.6:
        choice = rng.choice(["scale", "zero", "negate", "huge", "tiny", "nudge"])
        if choice == "scale":
            holder[key] = value * 10.0 ** rng.randint(-6, 6)
        elif choice == "zero":
            holder[key] = 0
        elif choice == "negate":
            holder[key] = -value
        elif choice == "huge":
            holder[key] = rng.choice([1e300, 1e30, 1e15, 2 ** 31, 2 ** 63])
        elif choice == "tiny":
            holder[key] = rng.choice([1e-300, 1e-15, 5e-324])
        else:
            holder[key] = value * (1 + rng.uniform(-0.5, 0.5))
    elif kind < 0.75 and isinstance(holder, dict):
        del holder[key]
    elif kind < 0.85:
        holder[key] = rng.choice(["", "x", True, None, [], {}, [0, 0], -1, "nan"])
    elif isinstance(value, list) and value:
        if rng.random() < 0.5:
            value.append(copy.deepcopy(rng.choice(value)))
        else:
            value.pop(rng.randrange(len(value)))
    else:
        holder[key] = rng.choice([0, 1, -1, "", None])


def non_finite(value, where):
    """The first inf or nan among the numbers of a parsed JSON document (strings do not count:
    a case's own text may read "nan")."""
    if isinstance(value, float) and not math.isfinite(value):
        return where
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list):
        items = enumerate(value)
    else:
        return ""
    for k, v in items:
        found = non_finite(v, f"{where}/{k}")
        if found:
            return found
    return ""


def files_finite(folder):
    """"" when every number written is finite and every JSON file parses, else where it is not."""
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name.endswith(".json"):
            try:
                with open(path) as f:
                    doc = json.load(f)  # Python reads NaN and Infinity as floats
            except ValueError as e:
                return f"{name}: not JSON ({e})"
            found = non_finite(doc, name)
            if found:
                return found
        elif name.endswith(".csv"):
            with open(path, errors="replace") as f:
                for row, line in enumerate(f, 1):
                    for field in line.strip().split(","):
                        try:
                            number = float(field)
                        except ValueError:
                            continue
                        if not math.isfinite(number):
                            return f"{name} line {row}: {field}"
    return ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--minutes", type=float, default=30)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", default="fuzz-findings")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cli = os.path.abspath(os.path.join(a.build, "ddaslope"))
    corpus = []
    for path in sorted(glob.glob(os.path.join(root, "cases", "*.json"))):
        with open(path) as f:
            corpus.append((os.path.basename(path), json.load(f)))
    rng = random.Random(a.seed)
    counts = {}
    defects = []
    work = tempfile.mkdtemp(prefix="ddaslope_fuzz_cli_")
    # The records and drawings the cases name, beside the mutated case as beside the shipped one.
    for entry in os.listdir(os.path.join(root, "cases")):
        if not entry.endswith(".json"):
            os.symlink(os.path.join(root, "cases", entry), os.path.join(work, entry))
    end = time.time() + 60 * a.minutes
    n = 0
    while time.time() < end:
        n += 1
        name, base = rng.choice(corpus)
        doc = copy.deepcopy(base)
        for _ in range(rng.randint(1, 2)):
            try:
                mutate(doc, rng)
            except (KeyError, IndexError, TypeError):
                pass
        command = rng.choice(["check", "run", "run", "fos", "critical"])
        case = os.path.join(work, "case.json")
        with open(case, "w") as f:
            json.dump(doc, f)
        out = os.path.join(work, "out")
        shutil.rmtree(out, ignore_errors=True)
        args = [cli, command, case]
        if command != "check":
            args += ["--out", out]
        if command == "critical":
            args += ["--solve", rng.choice(["cohesion", "friction"])]
        start = time.time()
        try:
            p = subprocess.run(args, cwd=work, capture_output=True, text=True,
                               timeout=LIMITS[command], errors="replace")
            code, err = p.returncode, p.stderr
        except subprocess.TimeoutExpired as e:
            code = "timeout"
            err = e.stderr.decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
        took = time.time() - start
        if code == "timeout":
            outcome = "stopped by the limit, said why" if SAID.search(err) else "DEFECT: silent past the limit"
        elif code in (0, 2, 3):
            outcome = f"exit {code}"
        elif code == 1:
            outcome = "DEFECT: exit 1 (internal error)"
        else:
            outcome = f"DEFECT: signal or exit {code}"
        if code in (0, 3) and os.path.isdir(out):
            bad = files_finite(out)
            if bad:
                outcome = f"DEFECT: non-finite number in {bad}"
        key = f"{command}: {outcome}"
        counts[key] = counts.get(key, 0) + 1
        if outcome.startswith("DEFECT"):
            os.makedirs(a.keep, exist_ok=True)
            kept = os.path.join(a.keep, f"defect_{a.seed}_{n}.json")
            shutil.copy(case, kept)
            defects.append(f"{kept}: {command} ({took:.0f} s): {outcome}\n    {err.strip()[-300:]}")
    shutil.rmtree(work, ignore_errors=True)
    print(f"fuzz_cli: {n} mutated cases in {a.minutes:g} min (seed {a.seed})")
    for k in sorted(counts):
        print(f"  {k}: {counts[k]}")
    for d in defects:
        print(d)
    return 1 if defects else 0


if __name__ == "__main__":
    sys.exit(main())
