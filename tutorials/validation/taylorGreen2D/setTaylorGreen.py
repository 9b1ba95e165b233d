#!/usr/bin/env python3
"""Sets the Taylor-Green velocity u = -U cos(2 pi x/L) sin(2 pi y/L), v = U sin(2 pi x/L)
cos(2 pi y/L) (ANALYTICAL.md; U = 1, L = the periodic length) on the particles of the newest
time directory's fluid.vtp (written by 'spindrift -dryRun'), in place. Needs VTK: run it with
pvpython (or a python3 with the vtk module).

    setTaylorGreen.py [U]
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

# etc/python/spindriftValidation.py, from $SPINDRIFT_DIR (exported by etc/RunFunctions) or this tree
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")) if d]
try:
    import spindriftValidation as sv
except ImportError as e:
    sys.exit("%s: %s: set SPINDRIFT_DIR to Spindrift's directory (source its etc/bashrc)" % (sys.argv[0], e))


def main():
    U = float(sys.argv[1]) if len(sys.argv) > 1 else 1.0
    path = os.path.join(sv.written_times()[-1][1], "fluid.vtp")
    data = sv.read_polydata(path)
    x = vtk_to_numpy(data.GetPoints().GetData())
    dx = np.diff(np.unique(np.round(x[:, 0], 12))).min()
    L = x[:, 0].max() - x[:, 0].min() + dx  # the lattice's extent + one spacing
    k = 2 * np.pi / L
    velocity = np.zeros_like(x)
    velocity[:, 0] = -U * np.cos(k * x[:, 0]) * np.sin(k * x[:, 1])
    velocity[:, 1] = U * np.sin(k * x[:, 0]) * np.cos(k * x[:, 1])
    array = numpy_to_vtk(velocity, deep=1)
    array.SetName("velocity")
    data.GetPointData().RemoveArray("velocity")
    data.GetPointData().AddArray(array)
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetHeaderTypeToUInt64()
    if writer.Write() != 1:
        sys.exit("cannot write " + path)
    print("setTaylorGreen: U = %g, L = %g on %d particles of %s" % (U, L, len(x), path))


if __name__ == "__main__":
    main()
