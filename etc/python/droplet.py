#!/usr/bin/env python3
"""A droplet without gravity at rest: its roundness, lost particles and Laplace pressure
(tutorials droplet2D and droplet3D).

    pvpython $SPINDRIFT_DIR/etc/python/droplet.py [case] [--from T] [--laplace-tolerance F] [--roundness-tolerance F]

Surface tension sigma pulls a square (cube) of fluid into a circle (sphere) of the same volume,
radius R from the particle count N: pi R^2 = N dx^2 in 2D, 4/3 pi R^3 = N dx^3 in 3D. At rest the
pressure inside is Laplace's jump across the surface, sigma/R in 2D (one curvature), 2 sigma/R in
3D (two), the outside pressure being 0.

Measured, at every written time from --from on (default: the last third of the run): the
roundness, the outline's largest radius over its smallest (the farthest particle from the
centroid in each of 36 sectors, or 100 cones in 3D: sqrt(2) for the square, 1 for a disc); the
particles farther than R + 3 dx from the centroid (escaped); the mean pressure
of the particles within R/2 of the centroid (with akinci2013, p + cohesionPressure when the case
writes it: a pairwise cohesion's own bulk pressure, which p balances). Checks: the mean of that pressure over those times
within --laplace-tolerance (5 %) of the jump, the last roundness within --roundness-tolerance
(2 %) of 1, no particle escaped. Exits 1 when a check fails.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import spindriftValidation as sv  # noqa: E402



def directions(d, count):
    """'count' unit vectors spread evenly: angles in 2D, Fibonacci points on the sphere in 3D."""
    k = np.arange(count) + 0.5
    if d == 2:
        return np.stack([np.cos(2 * np.pi * k / count), np.sin(2 * np.pi * k / count)], axis=1)
    z = 1 - 2 * k / count
    phi = np.pi * (3 - math.sqrt(5)) * k
    return np.stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z], axis=1)


def state(path, d):
    """(roundness, distances from the centroid, pressures) of one written time. The roundness is
    the outline's largest over its smallest radius: the farthest particle in each of 36 sectors
    (2D) or 100 cones about evenly spread directions (3D), each particle in the sector of the
    direction nearest its own (sqrt(2) for a square, sqrt(3) for a cube, 1 for a disc or ball)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    data = sv.read_polydata(path)
    if data.GetPointData().GetArray("pressure") is None:
        sys.exit("%s has no point array 'pressure'" % path)
    x, p = vtk_to_numpy(data.GetPoints().GetData()), vtk_to_numpy(data.GetPointData().GetArray("pressure"))
    cohesion = data.GetPointData().GetArray("cohesionPressure")
    if cohesion is not None:  # akinci2013: the mechanical pressure is p plus the cohesion's own
        p = p + vtk_to_numpy(cohesion)
    x = x[:, :d]
    r = x - x.mean(axis=0)
    dist = np.linalg.norm(r, axis=1)
    axes = directions(d, 36 if d == 2 else 100)
    sector = np.argmax(r @ axes.T, axis=1)
    outline = [dist[sector == k].max() for k in range(len(axes)) if np.any(sector == k)]
    return max(outline) / min(outline), dist, p


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", nargs="?", default=".")
    parser.add_argument("--from", dest="start", type=float, default=None,
                        help="the first time of the rest state (default: two thirds of the last written time)")
    parser.add_argument("--laplace-tolerance", type=float, default=0.05)
    parser.add_argument("--roundness-tolerance", type=float, default=0.02)
    args = parser.parse_args()
    props = sv.fluid_properties(args.case)
    d, dx = int(props["dimension"]), props["particleSpacing"]
    sigma = sv.surface_tension_sigma(args.case)
    times = sv.written_times(args.case)
    if len(times) < 2:
        sys.exit("no times written in %s" % args.case)
    start = args.start if args.start is not None else 2 * times[-1][0] / 3
    print("%8s %10s %12s %14s" % ("t [s]", "roundness", "beyond R+3dx", "p(r<R/2) [Pa]"))
    inner, roundness, escaped, R = [], None, 0, None
    for t, name in times:
        rnd, dist, p = state(os.path.join(args.case, name, "fluid.vtp"), d)
        n = len(dist)
        R = math.sqrt(n * dx * dx / math.pi) if d == 2 else (3 * n * dx ** 3 / (4 * math.pi)) ** (1 / 3)
        lost = int(np.sum(dist > R + 3 * dx))
        core = float(np.mean(p[dist < R / 2]))
        print("%8.4f %10.5f %12d %14.4f" % (t, rnd, lost, core))
        if t >= start - 1e-12:
            inner.append(core)
            roundness, escaped = rnd, max(escaped, lost)
    jump = (d - 1) * sigma / R
    mean = float(np.mean(inner))
    error = mean / jump - 1
    print("R = %.6g m (%d particles), sigma = %g N/m: Laplace jump %s = %.5g Pa" %
          (R, n, sigma, "sigma/R" if d == 2 else "2 sigma/R", jump))
    print("Figure: Laplace pressure, mean p(r < R/2) over t >= %g s: %.5g Pa, %+.2f %% (tolerance %.1f %%)" %
          (start, mean, 100 * error, 100 * args.laplace_tolerance))
    print("Figure: roundness at %g s: %.4f (tolerance %.1f %%); escaped particles: %d" %
          (times[-1][0], roundness, 100 * args.roundness_tolerance, escaped))
    failures = []
    if abs(error) > args.laplace_tolerance:
        failures.append("Laplace pressure %+.2f %% off" % (100 * error))
    if roundness - 1 > args.roundness_tolerance:
        failures.append("roundness %.4f" % roundness)
    if escaped:
        failures.append("%d particles escaped" % escaped)
    sv.finish(failures)


if __name__ == "__main__":
    main()
