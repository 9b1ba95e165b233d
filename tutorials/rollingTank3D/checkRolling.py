#!/usr/bin/env python3
"""The physics of rollingTank3D, from the times it wrote (run with pvpython, or a python3 with VTK).

    pvpython checkRolling.py [--volume 0.01] [--from 1.0]

At every written time:
  * the tank's pose, fitted to its particles (the rotation taking its particles at t = 0 to
    theirs at t, least squares: Kabsch), and its roll angle about y;
  * no fluid particle outside the tank: every fluid particle, mapped back into the tank's frame
    at t = 0, lies inside the tank's inner box (half a spacing of slack);
  * the fluid's volume, sum m/rho, within --volume of its start, and its particle count kept.
From --from on (the roll ramped up), the free surface's slope in the tank's frame (a line fitted
to the water's depth over 2-dx strips across the tank, from the particles' volume in each)
against the roll: the water stays near level
while the tank rolls under it, so that in the tank's frame its slope follows tan(roll) times
the amplification of linear sloshing's first mode, 1/(1 - (T1/T)^2) (within a factor 2), plus
the free oscillation of that mode the start left: a least-squares fit of the two explains the
slope (R^2 > 0.9). A surface that did not move with gravity would not tilt.
"""
import argparse
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.environ.get("SPINDRIFT_DIR", "../.."), "etc", "python"))
import spindriftValidation as sv  # noqa: E402

failures = []


def check(ok, message):
    print(("ok   " if ok else "FAIL ") + message)
    if not ok:
        failures.append(message)


def kabsch(p, q):
    """R, centroids with q ≈ R (p - cp) + cq."""
    cp, cq = p.mean(axis=0), q.mean(axis=0)
    u, _, vt = np.linalg.svd((p - cp).T @ (q - cq))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ np.diag([1, 1, d]) @ u.T
    return r, cp, cq


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--volume", type=float, default=0.01)
    ap.add_argument("--from", dest="start", type=float, default=1.0)
    a = ap.parse_args()
    props = sv.fluid_properties(".")
    dx, rho0 = props["particleSpacing"], props["rho0"]
    lo, hi = sv.geometry_box("walls", ".")
    geometry = open("constant/geometry").read()
    period = float(re.search(r"\bperiod\s+([-+0-9.eE]+)", geometry).group(1))
    L, depth = hi[0] - lo[0], sv.geometry_box("fluid", ".")[1][2] - lo[2]
    times = sv.written_times(".")
    tank0, ids0 = sv.read_vtp(os.path.join(times[0][1], "tank.vtp"), "id")
    tank0 = tank0[np.argsort(ids0)]
    x0, rho = sv.read_vtp(os.path.join(times[0][1], "fluid.vtp"), "density")
    n0, volume0 = len(x0), np.sum(rho0 * dx ** 3 / rho)
    angles, slopes, ts, worstOutside, worstVolume, lost = [], [], [], -np.inf, 0.0, 0
    for t, d in times:
        tank, ids = sv.read_vtp(os.path.join(d, "tank.vtp"), "id")
        r, cp, cq = kabsch(tank0, tank[np.argsort(ids)])
        fit = np.max(np.linalg.norm((tank0 - cp) @ r.T + cq - tank[np.argsort(ids)], axis=1))
        if fit > 1e-4:
            check(False, "t = %g: the tank's particles are not a rigid motion of its start (%.2g m off)" % (t, fit))
        angle = math.atan2(r[0, 2], r[0, 0])  # rotation about y: x' = cos a x + sin a z
        x, rho = sv.read_vtp(os.path.join(d, "fluid.vtp"), "density")
        lost = max(lost, n0 - len(x))
        worstVolume = max(worstVolume, abs(np.sum(rho0 * dx ** 3 / rho) / volume0 - 1))
        local = (x - cq) @ r + cp  # back into the tank's frame at t = 0
        outside = np.maximum(np.max(lo - 0.5 * dx - local, axis=1), np.max(local - hi - 0.5 * dx, axis=1))
        worstOutside = max(worstOutside, float(np.max(outside)))
        if t >= a.start:
            # the water's depth over each 2-dx strip across the tank, from its volume there
            width = 2 * dx
            bins = np.floor((local[:, 0] - lo[0]) / width).astype(int)
            nb = int(round((hi[0] - lo[0]) / width))
            counts = np.bincount(np.clip(bins, 0, nb - 1), minlength=nb)
            depth_x = counts * dx ** 3 / (width * (hi[1] - lo[1]))
            centres = lo[0] + width * (np.arange(nb) + 0.5)
            slopes.append(np.polyfit(centres[1:-1], depth_x[1:-1], 1)[0])  # the end strips: run-up
            angles.append(angle)
            ts.append(t)
    check(lost == 0, "fluid particles kept (%d lost)" % lost)
    check(worstOutside <= 0, "no fluid particle outside the rolling tank (the nearest to a face %.2g dx inside it)"
          % (-worstOutside / dx))
    check(worstVolume <= a.volume, "volume kept within %.2f %% (bound %.1f %%)" % (100 * worstVolume, 100 * a.volume))
    angles, slopes, ts = np.array(angles), np.array(slopes), np.array(ts)
    amplitude = math.degrees(np.max(np.abs(angles)))
    k = math.pi / L
    omega1 = math.sqrt(9.81 * k * math.tanh(k * depth))
    gain = 1 / (1 - (2 * math.pi / omega1 / period) ** 2)
    # linear sloshing: the forced response, gain tan(roll), plus the first mode's free oscillation
    # that the start left (at its natural frequency omega1), fitted by least squares
    basis = np.column_stack([np.tan(angles), np.cos(omega1 * ts), np.sin(omega1 * ts), np.ones_like(ts)])
    coef, *_ = np.linalg.lstsq(basis, slopes, rcond=None)
    fitted = basis @ coef
    r2 = 1 - np.sum((slopes - fitted) ** 2) / np.sum((slopes - slopes.mean()) ** 2)
    ratio, free = float(coef[0]), float(np.hypot(coef[1], coef[2]))
    print("roll amplitude %.2f deg; first sloshing mode T1 = %.3f s, forcing T = %g s: gain %.2f; free mode %.3f"
          % (amplitude, 2 * math.pi / omega1, period, gain, free))
    check(r2 > 0.9, "the surface's slope in the tank's frame is the forced and the free sloshing of linear theory: "
          "R^2 %.3f (bound 0.9)" % r2)
    check(0.5 * gain <= ratio <= 2 * gain,
          "the surface tilts with the roll: its forced slope in the tank's frame is %.2f times tan(roll) "
          "(linear sloshing: %.2f, band x0.5-x2)" % (ratio, gain))
    if os.environ.get("ROLL_DEBUG"):
        for row in zip(ts, np.tan(angles), slopes, fitted):
            print("%.3f %.4f %.4f %.4f" % row)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
