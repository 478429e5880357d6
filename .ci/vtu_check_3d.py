"""Interoperability check of a 3D run's ParaView output with an independent reader (meshio):
every file of the .pvd series is read; it must hold the model's nodes and its hexahedra (the
`hexahedra` of the recording's /model, node for node), and the displacement of every node at
every written increment must equal the recording's /positions minus the reference nodes
(`nodes_3d`) to 1e-12 of the body's size; the series has one file per recorded increment.

Usage: python .ci/vtu_check_3d.py RUN.pvd RUN.mcap
"""

import json
import pathlib
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np
from mcap.reader import make_reader


def read_mcap(path):
    model, positions = None, []
    with open(path, "rb") as f:
        for _, channel, message in make_reader(f).iter_messages(topics=["/model", "/positions"]):
            doc = json.loads(message.data)
            if channel.topic == "/model":
                model = doc
                continue
            # format 3: byte-shuffled doubles in hexadecimal, `dim` values per node
            planes = np.frombuffer(bytes.fromhex(doc["nodes"]), np.uint8).reshape(8, -1)
            positions.append(planes.T.copy().view("<f8").reshape(-1, doc["dim"]))
    return model, positions


def main():
    pvd, mcap = pathlib.Path(sys.argv[1]), sys.argv[2]
    model, positions = read_mcap(mcap)
    assert model["dim"] == 3, f"/model says dim = {model['dim']}"
    reference = np.array(model["nodes_3d"], dtype=float)
    hexahedra = np.array(model["hexahedra"], dtype=int)
    size = np.ptp(reference, axis=0).max()
    files = [pvd.parent / ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
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
    for p in problems:
        print("FAIL", p)
    print(f"vtu 3d: {len(files)} files, {len(hexahedra)} hexahedra, {len(reference)} nodes checked")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
