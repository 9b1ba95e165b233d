#!/usr/bin/env python3
"""The n = 2 oscillation of a 2D droplet: its period against Rayleigh's, damped by the viscosity.

    pvpython oscillation.py [case] [--tolerance F]

A 2D droplet of radius R (pi R^2 = N dx^2, N particles), surface tension sigma, density rho and
kinematic viscosity nu oscillates in its mode n with (Rayleigh 1879, in 2D; Lamb, Hydrodynamics,
art. 275, for a column of liquid)
    omega_0^2 = (n^3 - n) sigma / (rho R^3),
damped at the rate gamma = 2 n (n - 1) nu / R^2 (the energy of the mode's potential flow
dissipated by the viscosity), so its period is 2 pi / sqrt(omega_0^2 - gamma^2).

Measured: the elongation e = (<x^2> - <y^2>) / (<x^2> + <y^2>) of the particles about their
centroid at every written time; its zero crossings (interpolated linearly) after t = 0 are half
periods apart: the period is twice the mean spacing of the crossings. Checks: at least two
crossings, the period within --tolerance (5 %) of the damped one, the amplitude decaying. Exits 1
when a check fails.
"""
import argparse
import math
import os
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
    parser.add_argument("--tolerance", type=float, default=0.05)
    args = parser.parse_args()
    props = sv.fluid_properties(args.case)
    if int(props["dimension"]) != 2:
        sys.exit("oscillation.py compares a 2D droplet")
    dx, rho, nu = props["particleSpacing"], props["rho0"], props.get("viscosity", 0.0)
    sigma = sv.surface_tension_sigma(args.case)
    times, elongation, count = [], [], 0
    for t, name in sv.written_times(args.case):
        x, _ = sv.read_vtp(os.path.join(args.case, name, "fluid.vtp"), "velocity")
        r = x[:, :2] - x[:, :2].mean(axis=0)
        xx, yy = np.mean(r[:, 0] ** 2), np.mean(r[:, 1] ** 2)
        times.append(t)
        elongation.append((xx - yy) / (xx + yy))
        count = len(x)
    t, e = np.array(times), np.array(elongation)
    crossings = [t[k] - e[k] * (t[k + 1] - t[k]) / (e[k + 1] - e[k])
                 for k in range(1, len(t) - 1) if e[k] * e[k + 1] < 0]
    R = math.sqrt(count * dx * dx / math.pi)
    n = 2
    omega0 = math.sqrt((n ** 3 - n) * sigma / (rho * R ** 3))
    gamma = 2 * n * (n - 1) * nu / R ** 2
    period = 2 * math.pi / math.sqrt(omega0 ** 2 - gamma ** 2)
    print("R = %.5g m (%d particles), sigma %g N/m, nu %g m^2/s: Rayleigh's period %.5g s, damped %.5g s" %
          (R, count, sigma, nu, 2 * math.pi / omega0, period))
    print("zero crossings of the elongation [s]: " + " ".join("%.4f" % c for c in crossings))
    failures = []
    if len(crossings) < 2:
        print("FAILED: fewer than two zero crossings (no oscillation)")
        sys.exit(1)
    measured = 2 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    error = measured / period - 1
    peaks = [np.max(np.abs(e[(t > a) & (t < b)])) for a, b in zip(crossings[:-1], crossings[1:])]
    print("Figure: n = 2 period %.5g s against %.5g s (damped Rayleigh): %+.2f %% (tolerance %.1f %%)" %
          (measured, period, 100 * error, 100 * args.tolerance))
    print("Figure: elongation's peaks between crossings: " + " ".join("%.4f" % p for p in peaks))
    if abs(error) > args.tolerance:
        failures.append("period %+.2f %% off" % (100 * error))
    if len(peaks) >= 2 and not peaks[-1] < peaks[0]:
        failures.append("the oscillation does not decay (peaks %.4f then %.4f)" % (peaks[0], peaks[-1]))
    sv.finish(failures)


if __name__ == "__main__":
    main()
