#!/usr/bin/env python3
"""The diffuse particles of breakingWave3D: how many of each type over time, and their sanity.

    pvpython diffuse.py [case] [--after T] [--min-spray N] [--min-foam N]

At every written time: the number of spray (type 0), foam (1) and air-bubble (2) particles of
the passive system 'diffuse' (diffuse.vtp), their largest speed, foam's shortest remaining
lifetime. Checks: every particle inside the tank's box (constant/geometry's walls, with a
support's margin), ids unique at every time, foam's lifetime within (0, lifetime], and after
--after (default: the impact on the far wall, 0.5 s) at least --min-spray spray and --min-foam
foam particles at some time. Exits 1 when a check fails.
"""
import argparse
import os
import re
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
for d in (os.environ.get("SPINDRIFT_DIR", ""), os.path.join(here, "..", "..")):
    if os.path.exists(os.path.join(d, "etc", "python", "spindriftValidation.py")):
        sys.path.insert(0, os.path.join(d, "etc", "python"))
        break
import spindriftValidation as sv  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", nargs="?", default=".")
    parser.add_argument("--after", type=float, default=0.5)
    parser.add_argument("--min-spray", type=int, default=1)
    parser.add_argument("--min-foam", type=int, default=1)
    args = parser.parse_args()
    props = sv.fluid_properties(args.case)
    h = props["particleSpacing"] * props["supportRadius"]
    lo, hi = sv.geometry_box("walls", args.case)
    schemes = sv._dictionary_text(os.path.join(args.case, "system", "sphSchemes"))
    lifetime = float(re.search(r"\blifetime\s+([-+0-9.eE]+)\s*;", schemes).group(1))
    times = sv.written_times(args.case, "diffuse.vtp")
    if not times:
        sys.exit("no diffuse.vtp written in %s" % args.case)
    from vtkmodules.util.numpy_support import vtk_to_numpy
    failures = []
    most = {0: 0, 1: 0}
    print("%8s %8s %8s %8s %10s %12s" % ("t [s]", "spray", "foam", "bubbles", "max |v|", "min life"))
    for t, name in times:
        data = sv.read_polydata(os.path.join(args.case, name, "diffuse.vtp"))
        n = data.GetNumberOfPoints()
        if n == 0:
            print("%8.3f %8d %8d %8d" % (t, 0, 0, 0))
            continue
        x = vtk_to_numpy(data.GetPoints().GetData())
        pd = data.GetPointData()
        kind = vtk_to_numpy(pd.GetArray("type")).astype(int)
        life = vtk_to_numpy(pd.GetArray("lifetime"))
        v = vtk_to_numpy(pd.GetArray("velocity"))
        ids = vtk_to_numpy(pd.GetArray("id"))
        counts = [int(np.sum(kind == k)) for k in range(3)]
        foam = life[kind == 1]
        print("%8.3f %8d %8d %8d %10.3f %12s" % (t, counts[0], counts[1], counts[2], np.linalg.norm(v, axis=1).max(),
                                                 "%.3f" % foam.min() if len(foam) else "-"))
        if t > args.after:
            most[0], most[1] = max(most[0], counts[0]), max(most[1], counts[1])
        outside = np.any((x < lo - h) | (x > hi + h), axis=1)
        if np.any(outside):
            failures.append("%d diffuse particles outside the tank at t = %g" % (int(np.sum(outside)), t))
        if len(np.unique(ids)) != n:
            failures.append("ids not unique at t = %g" % t)
        if len(foam) and (foam.min() <= 0 or foam.max() > lifetime + 1e-9):
            failures.append("foam lifetime outside (0, %g] at t = %g" % (lifetime, t))
    print("Figure: most spray / foam particles at one time after %g s: %d / %d" % (args.after, most[0], most[1]))
    if most[0] < args.min_spray:
        failures.append("at most %d spray particles after %g s (at least %d)" % (most[0], args.after, args.min_spray))
    if most[1] < args.min_foam:
        failures.append("at most %d foam particles after %g s (at least %d)" % (most[1], args.after, args.min_foam))
    sv.finish(failures)


if __name__ == "__main__":
    main()
