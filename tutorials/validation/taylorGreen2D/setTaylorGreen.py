#!/usr/bin/env python3
"""Sets the Taylor-Green velocity u = -U cos(2 pi x/L) sin(2 pi y/L), v = U sin(2 pi x/L)
cos(2 pi y/L) (ANALYTICAL.md; U = 1, L = the periodic length) on the particles of the newest
time directory's fluid.vtp (written by 'spindrift -dryRun'), in place, with its pressure
p = -rho0 U^2/4 (cos(4 pi x/L) + cos(4 pi y/L)) and the density the Tait equation of state of
system/sphSchemes gives it, rho0 (p/B + 1)^(1/gamma), B = c0^2 rho0/gamma: a density integrated in
time (pressure 'density continuity;') starts in balance with the flow instead of sending out
pressure waves of amplitude rho0 U^2/4 (a velocity error of U^2/(4 c0)); a summed density is
computed from the positions anyway. An incompressible solver (no soundSpeed: pcisph, dfsph,
iisph, pbf, relaxedPbf) gets rho0 and the pressure, which those that warm-start begin from. Needs VTK: run it with pvpython (or a python3 with the vtk
module).

    setTaylorGreen.py [U]
"""
import os
import re
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


def equation_of_state():
    """(soundSpeed, gamma) of the pressure dictionary of system/sphSchemes (gamma 7 if not given)."""
    with open(os.path.join("system", "sphSchemes")) as fh:
        text = re.sub(r"//.*", "", fh.read())
    pressure = re.search(r"^pressure\s*\{([^}]*)\}", text, re.M).group(1)
    c0 = re.search(r"\bsoundSpeed\s+([^;\s]+)\s*;", pressure)
    gamma = re.search(r"\bgamma\s+([^;\s]+)\s*;", pressure)
    if c0 is None:
        return None, None  # an incompressible solver
    return float(c0.group(1)), float(gamma.group(1)) if gamma else 7.0


def set_array(data, name, values):
    array = numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    array.SetName(name)
    data.GetPointData().RemoveArray(name)
    data.GetPointData().AddArray(array)


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
    set_array(data, "velocity", velocity)
    rho0 = sv.fluid_properties()["rho0"]
    c0, gamma = equation_of_state()
    p = -rho0 * U ** 2 / 4 * (np.cos(2 * k * x[:, 0]) + np.cos(2 * k * x[:, 1]))
    set_array(data, "pressure", p)
    if c0 is None:
        set_array(data, "density", np.full(len(x), rho0))
    else:
        B = c0 ** 2 * rho0 / gamma
        set_array(data, "density", rho0 * (p / B + 1) ** (1 / gamma))
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    writer.SetHeaderTypeToUInt64()
    if writer.Write() != 1:
        sys.exit("cannot write " + path)
    eos = "c0 = %g, gamma = %g" % (c0, gamma) if c0 is not None else "incompressible: rho0"
    print("setTaylorGreen: U = %g, L = %g, pressure and density (%s) on %d particles of %s"
          % (U, L, eos, len(x), path))


if __name__ == "__main__":
    main()
