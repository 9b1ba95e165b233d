#!/usr/bin/env python3
"""The elliptical drop's semi-axes against the analytic solution (Monaghan 1994).

    pvpython semiAxes.py [case] [--tolerance F] [--minor-tolerance F]   (or a python3 with VTK)

A drop of radius R, velocity (-A x, A y) with A(0) = A0, stays an ellipse x^2/a^2 + y^2/b^2 <= 1
whose velocity field stays linear. With u = -A x, v = A y, Euler's equations with a pressure
p = rho P(t) (1 - x^2/a^2 - y^2/b^2) (zero on the surface) give
    (A^2 - dA/dt) a^2 = 2 P = (A^2 + dA/dt) b^2,
so (Monaghan 1994, "Simulating free surface flows with SPH", J. Comput. Phys. 110:399-406,
doi:10.1006/jcph.1994.1034, the elliptical drop; Colagrossi 2005, PhD thesis, same equations):
    dA/dt = A^2 (a^2 - b^2) / (a^2 + b^2),   da/dt = -A a,   db/dt = A b,   a b = R^2,
integrated here by RK4 (step 1e-7 s). At t = 0 (a = b = R) P = A0^2 R^2 / 2: the initial
pressure p = rho0 A0^2 (R^2 - x^2 - y^2) / 2 the case starts from.

Measured: each semi-axis from the particles' second moments about their centroid, which for a
uniform ellipse are <x^2> = a^2/4 and <y^2> = b^2/4 (a = 2 sqrt(<x^2>)); and, for comparison,
from the outermost particles (max |y| + dx/2). The checks, at every written time: the semi-major
axis b (moments) within --tolerance (1 %) of the analytic one, the semi-minor axis a within
--minor-tolerance (2 %). Exits 1 when a check fails.
"""
import argparse
import math
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


def analytic(t_end, A0, R, step=1e-7):
    """(A, a, b) at t_end: the ODE above by RK4."""
    def f(s):
        A, a, b = s
        return np.array([A * A * (a * a - b * b) / (a * a + b * b), -A * a, A * b])
    s = np.array([A0, R, R], dtype=float)
    n = max(1, int(math.ceil(t_end / step)))
    h = t_end / n
    for _ in range(n):
        k1 = f(s)
        k2 = f(s + 0.5 * h * k1)
        k3 = f(s + 0.5 * h * k2)
        k4 = f(s + h * k3)
        s = s + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return s


def geometry_numbers(case):
    """R and A0 from constant/geometry (radius; the factor of x in the first velocity expression)."""
    text = open(os.path.join(case, "constant", "geometry")).read()
    R = float(re.search(r"\bradius\s+([-+0-9.eE]+)\s*;", text).group(1))
    A0 = -float(re.search(r'\bvelocity\s*\(\s*"\s*([-+0-9.eE]+)\s*\*\s*x\s*"', text).group(1))
    return R, A0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", nargs="?", default=".")
    parser.add_argument("--tolerance", type=float, default=0.01,
                        help="relative error allowed of the semi-major axis b at every written time")
    parser.add_argument("--minor-tolerance", type=float, default=0.02,
                        help="relative error allowed of the semi-minor axis a at every written time")
    args = parser.parse_args()
    R, A0 = geometry_numbers(args.case)
    dx = sv.fluid_properties(args.case)["particleSpacing"]
    times = sv.written_times(args.case)
    if len(times) < 2:
        sys.exit("no times written in %s" % args.case)
    failures = []
    print("%8s %9s %9s %8s %9s %9s %9s %8s %9s %8s" % ("t [s]", "a", "a exact", "err a", "b", "b exact", "b edge",
                                                      "err b", "area/piR2", "A exact"))
    worst_a = worst_b = 0.0
    for t, d in times:
        x, _ = sv.read_vtp(os.path.join(args.case, d, "fluid.vtp"), "velocity")
        c = x.mean(axis=0)
        a = 2 * math.sqrt(np.mean((x[:, 0] - c[0]) ** 2))
        b = 2 * math.sqrt(np.mean((x[:, 1] - c[1]) ** 2))
        edge = np.max(np.abs(x[:, 1] - c[1])) + dx / 2
        A, a_ex, b_ex = analytic(t, A0, R)
        err_a, err_b = (a - a_ex) / a_ex, (b - b_ex) / b_ex
        worst_a, worst_b = max(worst_a, abs(err_a)), max(worst_b, abs(err_b))
        print("%8.4f %9.5f %9.5f %+7.3f%% %9.5f %9.5f %9.5f %+7.3f%% %9.5f %8.3f"
              % (t, a, a_ex, 100 * err_a, b, b_ex, edge, 100 * err_b, a * b / (R * R), A))
        if abs(err_b) > args.tolerance:
            failures.append("t = %g: semi-major axis b = %.5f m, analytic %.5f m: %+.2f %% (bound %g %%)"
                            % (t, b, b_ex, 100 * err_b, 100 * args.tolerance))
        if abs(err_a) > args.minor_tolerance:
            failures.append("t = %g: semi-minor axis a = %.5f m, analytic %.5f m: %+.2f %% (bound %g %%)"
                            % (t, a, a_ex, 100 * err_a, 100 * args.minor_tolerance))
    t, _ = times[-1]
    print("at t = %g: b %+.3f %% of the analytic; largest error over the run: b %.3f %% (bound %g %%), a %.3f %% "
          "(bound %g %%)" % (t, 100 * err_b, 100 * worst_b, 100 * args.tolerance, 100 * worst_a,
                             100 * args.minor_tolerance))
    for f in failures:
        print("FAILED: " + f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
