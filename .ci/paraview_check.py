"""What ParaView read of a 3D run's series (.ci/paraview_read.py, run by pvpython) against the
run's recording: one time step per recorded increment at its load level; the mesh part holds
the model's nodes and its hexahedra (VTK type 12, the `hexahedra` of /model node for node),
a displacement equal to /positions minus the reference nodes to 1e-12 of the model's size,
and the element fields (Cauchy stress, von Mises, Green–Lagrange strain) one value per
hexahedron, finite; the contact part holds the points of /surface_contact with their normal
forces and states.

Usage: python .ci/paraview_check.py PARAVIEW.json RUN.mcap
"""

import json
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).parent))
from vtu_check_3d import read_mcap  # noqa: E402

FIELDS = {"cauchy_stress": 9, "von_mises": 1, "green_lagrange_strain": 9}


def check_mesh(step, x, reference, hexahedra, size):
    mesh = step["parts"][0]
    problems = []
    if mesh["cell_types"] != [12]:
        problems.append(f"t = {step['t']}: cell types {mesh['cell_types']}, not hexahedra (12)")
    if not np.array_equal(np.array(mesh["connectivity"]).reshape(-1, 8), hexahedra):
        problems.append(f"t = {step['t']}: the hexahedra differ from /model")
    if not np.allclose(np.array(mesh["points"]), reference, rtol=0, atol=1e-12 * size):
        problems.append(f"t = {step['t']}: the points are not the reference nodes")
    err = np.abs(np.array(mesh["arrays"]["displacement"]) - (x - reference)).max()
    if err > 1e-12 * size:
        problems.append(f"t = {step['t']}: displacement off the recording by {err:.3e}")
    for name, width in FIELDS.items():
        values = np.array(mesh["cell_arrays"].get(name, []), dtype=float).reshape(len(hexahedra), -1)
        if values.shape[1] != width or not np.isfinite(values).all():
            problems.append(f"t = {step['t']}: cell field {name} missing, of the wrong width or not finite")
    return problems


def check_contact(step, points, size):
    contact = step["parts"][1]
    a = contact["arrays"]
    problems = []
    if not np.allclose(np.array(contact["points"]), np.array(points["position"]), rtol=0, atol=1e-12 * size):
        problems.append(f"t = {step['t']}: contact points differ from /surface_contact")
    if not np.allclose(a["normal_traction"], points["normal_force"], rtol=1e-14, atol=0, equal_nan=True):
        problems.append(f"t = {step['t']}: normal_traction differs from /surface_contact")
    if not np.array_equal(np.array(a["state"]), np.array(points["state"])):
        problems.append(f"t = {step['t']}: state differs from /surface_contact")
    return problems


def main():
    seen = json.loads(pathlib.Path(sys.argv[1]).read_text())
    model, positions, surface = read_mcap(sys.argv[2])
    reference = np.array(model["nodes_3d"], dtype=float)
    hexahedra = np.array(model["hexahedra"], dtype=int)
    size = np.ptp(reference, axis=0).max()
    steps = seen["steps"]
    problems = []
    if len(steps) != len(positions):
        problems.append(f"ParaView read {len(steps)} time steps for {len(positions)} recorded increments")
    for k, (step, x) in enumerate(zip(steps, positions)):
        problems += check_mesh(step, x, reference, hexahedra, size)
        if surface:
            problems += check_contact(step, surface[k + 1], size)
    for p in problems:
        print("FAIL", p)
    print(f"paraview ({seen['reader']}): {len(steps)} time steps, {len(hexahedra)} hexahedra, {len(reference)} nodes checked")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
