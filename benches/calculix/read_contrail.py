#!/usr/bin/env python3
"""Read a contrail run of `hertz-3d` written with `--out RUN.jsonl` and print the Hertz
measures of `hertz_ref.py`, computed as tests/hertz_sphere_3d.rs computes them: the
`surface_contact_point` records after the last `increment` record, those not `open`, their
`normal_force` and `position`; the node on the axis's force over its tributary area (the
reference area of the block's top face around it, as contrail's `tributary_areas`).

  read_contrail.py RUN.jsonl NX NY NZ
Exits non-zero if the run did not complete or a number is missing.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz_ref import measure, report  # noqa: E402
from hertz_3d_inp import block_grid  # noqa: E402


def fail(msg):
    print(f"read_contrail: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    if len(sys.argv) != 5:
        fail("usage: read_contrail.py RUN.jsonl NX NY NZ")
    path, elements = sys.argv[1], [int(v) for v in sys.argv[2:5]]
    run, points, outcome, iterations = None, [], None, 0
    for raw in open(path):
        r = json.loads(raw)
        kind = r["kind"]
        if kind == "run":
            run = r["data"]
        elif kind == "increment":
            points = []
            if r["data"].get("converged"):
                iterations += r["data"]["iterations"]
        elif kind == "surface_contact_point":
            points.append(r["data"])
        elif kind == "outcome":
            outcome = r["data"]
    if run is None or outcome is None or outcome.get("status") != "completed":
        fail(f"the run did not complete: {outcome}")
    # the block's top-face grid: tributary areas in the reference configuration
    xs, ys, _ = block_grid(elements)
    nx, ny = elements[0], elements[1]

    def area(node):
        """The reference tributary area of block node `node` (numbered x fastest, then y)."""
        i, j = node % (nx + 1), (node // (nx + 1)) % (ny + 1)
        wx = (xs[min(i + 1, nx)] - xs[max(i - 1, 0)]) / 2.0
        wy = (ys[min(j + 1, ny)] - ys[max(j - 1, 0)]) / 2.0
        return wx * wy

    closed = [p for p in points if p["state"] != "open"]
    pts = []
    for p in closed:
        x, y = p["position"][0], p["position"][1]
        pts.append((x, y, p["normal_force"], area(p["node"])))
    m = measure(pts)
    extra = {"unknowns": run.get("free_dofs", "?"), "iterations": iterations}
    report("contrail", path, m, extra)

if __name__ == "__main__":
    main()
