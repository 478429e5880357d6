"""Interoperability check of a 3D run's ParaView output with an independent reader (meshio):
every file of the .pvd series is read; it must hold the model's nodes and its hexahedra (the
`hexahedra` of the recording's /model, node for node), and the displacement of every node at
every written increment must equal the recording's /positions minus the reference nodes
(`nodes_3d`) to 1e-12 of the body's size; the series has one file per recorded increment.
Where the run has 3D contact, each increment's contact file (part 1) must hold the points of
/surface_contact: positions, normal forces (`normal_traction`), facets (-1: none) and state
codes (0 open, 1 stick, 2 slip) equal to the recording's.

Usage: python .ci/vtu_check_3d.py RUN.pvd RUN.mcap
"""

import json
import pathlib
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np
from mcap.reader import make_reader


STATES = {"open": 0, "stick": 1, "slip": 2}


def real(x):
    return float(x)  # "NaN", "Infinity" and numbers alike


def read_mcap(path):
    model, positions, surface = None, [], {}
    with open(path, "rb") as f:
        topics = ["/model", "/positions", "/surface_contact"]
        for _, channel, message in make_reader(f).iter_messages(topics=topics):
            doc = json.loads(message.data)
            if channel.topic == "/model":
                model = doc
                continue
            if channel.topic == "/surface_contact":
                points = surface.setdefault(doc["increment"], {"position": [], "normal_force": [], "facet": [], "state": []})
                points["position"] += [[real(c) for c in p] for p in doc["position"]]
                points["normal_force"] += [real(n) for n in doc["normal_force"]]
                points["facet"] += [-1 if f is None else f for f in doc["facet"]]
                points["state"] += [STATES[s] for s in doc["state"]]
                continue
            # format 3: byte-shuffled doubles in hexadecimal, `dim` values per node
            planes = np.frombuffer(bytes.fromhex(doc["nodes"]), np.uint8).reshape(8, -1)
            positions.append(planes.T.copy().view("<f8").reshape(-1, doc["dim"]))
    return model, positions, surface


def check_contact(file, points, size):
    """Problems of the contact file of one increment against its /surface_contact points."""
    mesh = meshio.read(file)
    pd = mesh.point_data
    problems = []
    if len(mesh.points) != len(points["position"]):
        return [f"{file.name}: {len(mesh.points)} contact points, the recording {len(points['position'])}"]
    if not np.allclose(mesh.points, np.array(points["position"]), rtol=0, atol=1e-12 * size):
        problems.append(f"{file.name}: contact point positions differ from /surface_contact")
    if not np.allclose(pd["normal_traction"], points["normal_force"], rtol=1e-14, atol=0, equal_nan=True):
        problems.append(f"{file.name}: normal_traction differs from /surface_contact normal_force")
    for name in ("facet", "state"):
        if not np.array_equal(pd[name], np.array(points[name])):
            problems.append(f"{file.name}: {name} differs from /surface_contact")
    return problems


def main():
    pvd, mcap = pathlib.Path(sys.argv[1]), sys.argv[2]
    model, positions, surface = read_mcap(mcap)
    assert model["dim"] == 3, f"/model says dim = {model['dim']}"
    reference = np.array(model["nodes_3d"], dtype=float)
    hexahedra = np.array(model["hexahedra"], dtype=int)
    size = np.ptp(reference, axis=0).max()
    datasets = list(ET.parse(pvd).getroot().iter("DataSet"))
    files = [pvd.parent / ds.get("file") for ds in datasets if ds.get("part") == "0"]
    contact_files = [pvd.parent / ds.get("file") for ds in datasets if ds.get("part") == "1"]
    problems = []
    if len(files) != len(positions):
        problems.append(f"{len(files)} VTU files for {len(positions)} recorded increments")
    for file, x in zip(files, positions):
        mesh = meshio.read(file)
        cells = [c.data for c in mesh.cells if c.type == "hexahedron"]
        if len(cells) != 1 or not np.array_equal(cells[0], hexahedra):
            problems.append(f"{file.name}: the hexahedra differ from the recording's /model")
        if not np.allclose(mesh.points, reference, rtol=0, atol=1e-12 * size):
            problems.append(f"{file.name}: points are not the reference nodes")
        u = mesh.point_data["displacement"]
        err = np.abs(u - (x - reference)).max()
        if err > 1e-12 * size:
            problems.append(f"{file.name}: displacement off the recording by {err:.3e}")
    if surface:
        if len(contact_files) != len(positions):
            problems.append(f"{len(contact_files)} contact files for {len(positions)} recorded increments")
        for file in contact_files:
            inc = int(file.stem.rsplit("_", 1)[1])  # RUN_contact_000012
            problems += check_contact(file, surface[inc], size) if inc in surface else [f"{file.name}: no /surface_contact"]
    for p in problems:
        print("FAIL", p)
    print(f"vtu 3d: {len(files)} mesh and {len(contact_files)} contact files, {len(hexahedra)} hexahedra, {len(reference)} nodes checked")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
