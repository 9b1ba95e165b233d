#!/usr/bin/env python3
"""taylorGreen2D: the decaying Taylor-Green vortex against its exact solution (ANALYTICAL.md):
u = -U e^{bt} cos(2 pi x/L) sin(2 pi y/L), v = U e^{bt} sin(2 pi x/L) cos(2 pi y/L),
b = -8 pi^2 nu / L^2.

Reads the written time directories (fluid.vtp, with VTK: run it with pvpython) and
postProcessing/stats, prints 'Figure: name = value' lines (the first is the case's error
figure, read by spindriftBench) and draws taylorGreen2D.png (unless --no-plot or
SPINDRIFT_NO_PLOT=1).
Figures:
  velocityL2      the largest relative L2 error of the particle velocities over the written
                  times, sqrt(sum_i |u_i - u_exact(x_i, t)|^2 / sum_i |u_exact(x_i, t)|^2)
  maxSpeedError   relative error of the largest particle speed against U e^{bt} at t = 1
  energyError     relative error of the kinetic energy against E0 e^{2bt} at the end
"""
import os
import sys

import numpy as np

# etc/python/spindriftValidation.py, from $SPINDRIFT_DIR (exported by etc/RunFunctions) or this tree
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")) if d]
try:
    import spindriftValidation as sv
except ImportError as e:
    sys.exit("%s: %s: set SPINDRIFT_DIR to Spindrift's directory (source its etc/bashrc)" % (sys.argv[0], e))


def main():
    props = sv.fluid_properties()
    nu, dx = props["viscosity"], props["particleSpacing"]
    lo, hi = sv.periodic_extent("x")
    L = hi - lo
    k = 2 * np.pi / L
    b = -8 * np.pi ** 2 * nu / L ** 2

    def exact(x, t):
        e = np.exp(b * t)
        return np.stack([-e * np.cos(k * x[:, 0]) * np.sin(k * x[:, 1]), e * np.sin(k * x[:, 0]) * np.cos(k * x[:, 1])], axis=1)

    written = [(t, d) for t, d in sv.written_times() if t > 0]
    if not written:
        sys.exit("no time directory after t = 0")
    errors = []
    for t, d in written:
        x, u = sv.read_vtp(os.path.join(d, "fluid.vtp"))
        ue = exact(x, t)
        errors.append((t, np.sqrt(np.sum((u[:, :2] - ue) ** 2) / np.sum(ue ** 2))))
    l2 = max(e for _, e in errors)
    stats = sv.read_dat("stats")
    ts, speed, ke = stats.time, stats["maxSpeed"], stats["kineticEnergy"]
    i1 = int(np.argmin(np.abs(ts - 1.0)))
    speed_error = (speed[i1] - np.exp(b * ts[i1])) / np.exp(b * ts[i1])
    energy_error = (ke[-1] / ke[0] - np.exp(2 * b * ts[-1])) / np.exp(2 * b * ts[-1])
    print("Figure: velocityL2 = %.4f (largest relative L2 error of the particle velocities at t = %s)"
          % (l2, ", ".join("%g" % t for t, _ in errors)))
    for t, e in errors:
        print("    t = %g: L2 = %.4f" % (t, e))
    print("Figure: maxSpeedError = %.4f (max speed %.4f at t = %.3g, exact %.4f)"
          % (speed_error, speed[i1], ts[i1], np.exp(b * ts[i1])))
    print("Figure: energyError = %.4f (E/E0 = %.4f at t = %.3g, exact %.4f)"
          % (energy_error, ke[-1] / ke[0], ts[-1], np.exp(2 * b * ts[-1])))

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, (a, c) = plt.subplots(1, 2, figsize=(12, 4.8))
    tt = np.linspace(0, ts[-1], 200)
    a.semilogy(tt, np.exp(b * tt), "k-", lw=1, label="exact $U e^{bt}$")
    a.semilogy(ts, speed, "C0o", ms=3, label="SPH max speed")
    a.semilogy(tt, np.exp(2 * b * tt), "k--", lw=1, label="exact $E/E_0 = e^{2bt}$")
    a.semilogy(ts, ke / ke[0], "C1s", ms=3, label="SPH $E/E_0$")
    a.set_xlabel("t [s]")
    a.set_ylabel("max speed / U, kinetic energy / $E_0$ [-]")
    a.set_title("decay against the exact solution (U = 1 m/s, Re = %.0f, L/dx = %.0f)" % (L / nu, L / dx), fontsize=10)
    a.legend(loc="lower left", fontsize=8)
    a.grid(alpha=0.3, which="both")
    t_last, d_last = written[-1]
    x, u = sv.read_vtp(os.path.join(d_last, "fluid.vtp"))
    s = np.sqrt(u[:, 0] ** 2 + u[:, 1] ** 2)
    sc = c.scatter(x[:, 0], x[:, 1], c=s, s=5, cmap="viridis", rasterized=True)
    # arrows: the particles' mean velocity in cells of about 16 particles, at most 16 x 16 of them
    # (one arrow per particle would hide the particles)
    cells = max(4, min(16, int(np.sqrt(len(x)) / 4)))
    lo, hi = x[:, :2].min(axis=0), x[:, :2].max(axis=0)
    k = np.clip(((x[:, :2] - lo) / (hi - lo + 1e-12) * cells).astype(int), 0, cells - 1)
    cell = k[:, 0] * cells + k[:, 1]
    count = np.bincount(cell, minlength=cells * cells)
    filled = count > 0
    mean = [np.bincount(cell, weights=w, minlength=cells * cells)[filled] / count[filled]
            for w in (x[:, 0], x[:, 1], u[:, 0], u[:, 1])]
    c.quiver(*mean, scale=12 * np.exp(b * t_last), width=0.004, color="w", edgecolor="k", linewidth=0.4)
    c.set_aspect("equal")
    c.set_xlabel("x [m]")
    c.set_ylabel("y [m]")
    c.set_title("t = %g s: particles (colour: speed), arrows: mean velocity\nof %d x %d cells; L2 error %.3f"
                % (t_last, cells, cells, errors[-1][1]), fontsize=10)
    fig.colorbar(sc, ax=c, label="particle speed |u| [m/s]")
    fig.tight_layout()
    print("Plot: " + sv.save(fig, "taylorGreen2D.png"))


if __name__ == "__main__":
    main()
