"""Runs the numpy snippet of docs/recording.md on recordings and checks what it returns
against the messages read independently: one entry per increment, arrays as long as the
message's `slave` list, NaN where the recording has the string "NaN", and the history of a
recording written with `--all-points` complete.

Usage: python .ci/snippet_check.py SNIPPET.py RUN.mcap [ALL_POINTS.mcap]
"""

import json
import math
import sys

import numpy as np
from mcap.reader import make_reader


def raw(path):
    msgs, model = [], None
    with open(path, "rb") as f:
        for _, channel, m in make_reader(f).iter_messages(topics=["/contact", "/model"]):
            doc = json.loads(m.data)
            if channel.topic == "/model":
                model = doc
            else:
                msgs.append(doc)
    return model, msgs


def check(ns, path, complete):
    problems = []
    model, msgs = raw(path)
    for pair in model["contacts"]:
        name, slaves = pair["name"], len(pair["slaves"])
        points = ns["contact"](path, name)
        mine = [m for m in msgs if m["pair_name"] == name]
        if sorted(points) != sorted(m["increment"] for m in mine):
            problems.append(f"{path} {name}: increments differ")
            continue
        for m in mine:
            p = points[m["increment"]]
            if list(p["slave"]) != m["slave"] or p["position"].shape != (len(m["slave"]), 2):
                problems.append(f"{path} {name} increment {m['increment']}: slaves or positions differ")
                break
            gap = [float(x) for x in m["gap"]]
            if not all((math.isnan(a) and math.isnan(b)) or a == b for a, b in zip(gap, p["gap"])):
                problems.append(f"{path} {name} increment {m['increment']}: gap differs")
                break
        incs, h = ns["history"](points, "normal_force", slaves)
        if h.shape != (len(mine), slaves):
            problems.append(f"{path} {name}: history of shape {h.shape}")
        if complete and np.isnan(h).any():
            problems.append(f"{path} {name}: a recording with every point has gaps in its history")
    return problems


def main():
    ns = {}
    exec(open(sys.argv[1]).read(), ns)
    problems = check(ns, sys.argv[2], complete=False)
    if len(sys.argv) > 3:
        problems += check(ns, sys.argv[3], complete=True)
    for p in problems:
        print(p)
    print(f"docs snippet: {1 if not problems else 0} passed, {1 if problems else 0} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
