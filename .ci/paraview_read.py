"""Read a run's ParaView series with ParaView itself (pvpython: its PVD reader, as the GUI's
File > Open does) and write what it read as JSON, for .ci/paraview_check.py to compare with
the run's recording: per time step of the series, the mesh part's points, cell types,
connectivity, point and cell arrays, and the contact part's points and arrays.

Usage: pvpython .ci/paraview_read.py RUN.pvd OUT.json
"""

import json
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile
from vtkmodules.util.numpy_support import vtk_to_numpy


def arrays(fields):
    return {fields.GetArrayName(k): vtk_to_numpy(fields.GetArray(k)).tolist() for k in range(fields.GetNumberOfArrays())}


def leaves(data):
    """The datasets of a (nested) multiblock, in order."""
    if data is None:
        return []
    if data.IsA("vtkMultiBlockDataSet"):
        return [leaf for k in range(data.GetNumberOfBlocks()) for leaf in leaves(data.GetBlock(k))]
    return [data]


def part(data):
    cells = data.GetCells()
    return {
        "class": data.GetClassName(),
        "points": vtk_to_numpy(data.GetPoints().GetData()).tolist() if data.GetNumberOfPoints() else [],
        "cell_types": sorted({data.GetCellType(k) for k in range(data.GetNumberOfCells())}),
        "connectivity": vtk_to_numpy(cells.GetConnectivityArray()).tolist() if cells is not None else [],
        "arrays": arrays(data.GetPointData()),
        "cell_arrays": arrays(data.GetCellData()),
    }


def main():
    reader = OpenDataFile(sys.argv[1])
    steps = []
    for t in reader.TimestepValues:
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        steps.append({"t": t, "parts": [part(b) for b in leaves(data)]})
    with open(sys.argv[2], "w") as f:
        json.dump({"reader": reader.GetXMLName(), "steps": steps}, f)
    print(f"paraview {reader.GetXMLName()}: {len(steps)} time steps of {sys.argv[1]} read")


if __name__ == "__main__":
    main()
