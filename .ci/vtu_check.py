"""Interoperability check of contrail's ParaView output with an independent reader (meshio):
every file of a .pvd series is read, its arrays must have the expected names and shapes, and
the values must agree with the same run's MCAP recording and CSV file:

- the displacement of every node at every written increment equals the recording's
  /positions minus the reference nodes of /model (to 1e-12 of the size of the body);
- the monitored displacement in the CSV (mean u_y of the face `top`, sign −1) and the
  monitored force (the sum of the contact points' normal tractions) agree to 1e-9;
- von Mises recomputed here from the Cauchy tensor equals the written one (1e-9);
- the series has the increments asked for (`--every N`: every N-th and the last).

Usage: python .ci/vtu_check.py RUN.pvd RUN.mcap RUN.csv [--every N] [--fields|--no-fields]
"""

import argparse
import csv
import json
import pathlib
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np
from mcap.reader import make_reader


def read_pvd(path):
    root = ET.parse(path).getroot()
    steps = {}
    for ds in root.iter("DataSet"):
        t = float(ds.get("timestep"))
        part = int(ds.get("part"))
        steps.setdefault(t, {})[part] = path.parent / ds.get("file")
    return steps


def read_mcap(path):
    model, positions = None, {}
    with open(path, "rb") as f:
        for _, channel, message in make_reader(f).iter_messages(topics=["/model", "/positions"]):
            doc = json.loads(message.data)
            if channel.topic == "/model":
                model = doc
            else:
                if isinstance(doc["nodes"], str):
                    # format 3: byte-shuffled doubles in hexadecimal (schemas/positions.schema.json)
                    planes = np.frombuffer(bytes.fromhex(doc["nodes"]), np.uint8).reshape(8, -1)
                    doc["nodes"] = planes.T.copy().view("<f8").reshape(-1, 2)
                positions[doc["increment"]] = doc
    return model, positions


def check(args):
    problems = []
    steps = read_pvd(pathlib.Path(args.pvd))
    model, positions = read_mcap(args.mcap)
    rows = list(csv.DictReader(open(args.csv)))
    reference = np.array(model["nodes"], dtype=float)
    size = np.ptp(reference, axis=0).max()
    top = sorted({n for f in model["bodies"][0]["faces"] if f["name"] == "top" for s in f["segments"] for n in s})
    n_inc = len(rows)
    expected = sorted({k for k in range(1, n_inc + 1) if k % args.every == 0} | {n_inc})
    if len(steps) != len(expected):
        problems.append(f"{len(steps)} time steps in the .pvd, expected {len(expected)} (increments {expected})")
    def row_at(t):
        # the CSV has 11 significant digits, the .pvd the exact load level
        near = [r for r in rows if abs(float(r["t"]) - t) <= 1e-9 * max(1.0, abs(t))]
        return near[0] if len(near) == 1 else None

    for t, parts in sorted(steps.items()):
        mesh = meshio.read(parts[0])
        u = mesh.point_data.get("displacement")
        if u is None or u.shape != (len(reference), 3):
            problems.append(f"t = {t}: displacement {None if u is None else u.shape}, expected ({len(reference)}, 3)")
            continue
        if [c.type for c in mesh.cells] != ["quad"] or len(mesh.cells[0].data) != len(model["elements"]):
            problems.append(f"t = {t}: cells {[(c.type, len(c.data)) for c in mesh.cells]}")
        row = row_at(t)
        if row is None:
            problems.append(f"t = {t}: no CSV row at this load level")
            continue
        inc = int(row["increment"])
        if inc in positions:
            expect = np.array(positions[inc]["nodes"], dtype=float) - reference
            err = np.abs(u[:, :2] - expect).max()
            if err > 1e-12 * size:
                problems.append(f"increment {inc}: displacement differs from /positions by {err:.3e}")
        mean_uy = -u[top, 1].mean()
        if abs(mean_uy - float(row["displacement"])) > 1e-9 * max(1.0, abs(mean_uy)):
            problems.append(f"increment {inc}: mean u_y of `top` {mean_uy!r}, CSV {row['displacement']}")
        if args.fields:
            cd = {k: v[0] for k, v in mesh.cell_data.items()}
            for name, shape in [("cauchy_stress", (len(model["elements"]), 9)),
                                ("green_lagrange_strain", (len(model["elements"]), 9)),
                                ("von_mises", (len(model["elements"]),)), ("body", (len(model["elements"]),))]:
                if name not in cd or cd[name].shape != shape:
                    problems.append(f"increment {inc}: cell data {name} {cd.get(name, np.array([])).shape}, expected {shape}")
            if "cauchy_stress" in cd and "von_mises" in cd:
                s = cd["cauchy_stress"].reshape(-1, 3, 3)
                sx, sy, sz, txy = s[:, 0, 0], s[:, 1, 1], s[:, 2, 2], s[:, 0, 1]
                vm = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3 * txy ** 2)
                err = np.abs(vm - cd["von_mises"]).max()
                if not err <= 1e-9 * max(1.0, np.abs(vm).max()):
                    problems.append(f"increment {inc}: von Mises differs from the Cauchy tensor's by {err:.3e}")
                if not np.allclose(s, s.transpose(0, 2, 1)):
                    problems.append(f"increment {inc}: Cauchy stress not symmetric")
        contact = meshio.read(parts[1])
        pd = contact.point_data
        n = len(contact.points)
        for name, shape in [("gap", (n,)), ("normal_traction", (n,)), ("tangential_traction", (n,)),
                            ("trial_traction", (n,)), ("state", (n,)), ("segment", (n,)), ("pair", (n,)),
                            ("normal", (n, 3))]:
            if name not in pd or pd[name].shape != shape:
                problems.append(f"increment {inc}: contact point data {name} {pd.get(name, np.array([])).shape}, expected {shape}")
        if "normal_traction" in pd:
            force = pd["normal_traction"].sum()
            if abs(force - float(row["force"])) > 1e-9 * max(1.0, abs(force)):
                problems.append(f"increment {inc}: sum of normal tractions {force!r}, CSV force {row['force']}")
        if "state" in pd and "normal_traction" in pd:
            closed = int((pd["state"] > 0).sum())
            if closed != int(row["contact_closed"]):
                problems.append(f"increment {inc}: {closed} closed contact points, CSV {row['contact_closed']}")
    return problems


def main():
    p = argparse.ArgumentParser()
    p.add_argument("pvd")
    p.add_argument("mcap")
    p.add_argument("csv")
    p.add_argument("--every", type=int, default=1)
    p.add_argument("--fields", action=argparse.BooleanOptionalAction, default=True)
    args = p.parse_args()
    problems = check(args)
    for pr in problems:
        print(f"{args.pvd}: {pr}")
    if problems:
        sys.exit(1)
    print(f"{args.pvd}: ok ({len(read_pvd(pathlib.Path(args.pvd)))} time steps read with meshio {meshio.__version__})")


if __name__ == "__main__":
    main()
