#!/usr/bin/env python3
"""poiseuille2D: particle velocities against the series solution of Morris, Fox & Zhu (1997).

    v_x(y, t) = F/(2 nu) y (L - y)
                - sum_n 4 F L^2 / (nu pi^3 (2n+1)^3) sin((2n+1) pi y / L) exp(-(2n+1)^2 pi^2 nu t / L^2)

Reads the written time directories (fluid.vtp, with VTK: run it with pvpython or a python3
that has the vtk module) and postProcessing/centre (a probe on the centre line), prints
'Figure: name = value' lines (the first is the case's error figure, read by spindriftBench)
and draws poiseuille2D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).
Figures:
  velocityL2     the largest relative L2 error over the particles, sqrt(sum_i (u_i -
                 u_exact(y_i))^2 / sum_i u_exact(y_i)^2), at the reference check times 0.0225,
                 0.045, 0.1125, 0.225 s and at the end
  centreError    relative error of the centre-line probe velocity at the end
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


def exact(y, t, F, nu, L):
    v = F / (2 * nu) * y * (L - y)
    for n in range(200):
        k = 2 * n + 1
        v = v - 4 * F * L ** 2 / (nu * np.pi ** 3 * k ** 3) * np.sin(k * np.pi * y / L) * np.exp(-k * k * np.pi ** 2 * nu * t / L ** 2)
    return v


def main():
    props = sv.fluid_properties()
    F, nu, dx = props["gravity"][0], props["viscosity"], props["particleSpacing"]
    L = sv.geometry_box("fluid")[1][1]

    written = sv.written_times()
    end = written[-1][0]
    checks = [c for c in (0.0225, 0.045, 0.1125, 0.225) if c < end - 1e-9] + [end]
    results = []
    for tc in checks:
        t, d = min(written, key=lambda w: abs(w[0] - tc))
        x, u = sv.read_vtp(os.path.join(d, "fluid.vtp"))
        ue = exact(x[:, 1], t, F, nu, L)
        results.append((t, np.sqrt(np.sum((u[:, 0] - ue) ** 2) / np.sum(ue ** 2)), x[:, 1], u[:, 0]))
    l2 = max(r[1] for r in results)
    centre = sv.read_dat("centre")
    probe = centre["Ux(0.00025,0.0005)"]
    uc, tc = probe[-1], centre.time[-1]
    uce = exact(np.array(L / 2), tc, F, nu, L)
    print("Figure: velocityL2 = %.4f (largest relative L2 error over the particles at t = %s s)"
          % (l2, ", ".join("%.4g" % r[0] for r in results)))
    for t, e, _, _ in results:
        print("    t = %.4g s: L2 = %.4f" % (t, e))
    print("Figure: centreError = %.4f (centre-line probe %.4g m/s, exact %.4g m/s at t = %.3g s)"
          % ((uc - uce) / uce, uc, uce, tc))

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6))
    yy = np.linspace(0, L, 200)
    for j, (t, e, y, u) in enumerate(results):
        ax.plot(exact(yy, t, F, nu, L) * 1e6, yy * 1e3, "-", color="C%d" % j, lw=1)
        ax.plot(u * 1e6, y * 1e3, ".", color="C%d" % j, ms=3, label="t = %.4g s (L2 %.3f)" % (t, e))
    ax.set_xlabel("$v_x$ [$\\mu$m/s]")
    ax.set_ylabel("y [mm]")
    ax.set_title("particles (dots) against the series solution (lines)", fontsize=10)
    sv.legend_beside(ax)
    ax.grid(alpha=0.3)
    tt = np.linspace(0, centre.time[-1], 200)
    bx.plot(tt, exact(np.array(L / 2), tt, F, nu, L) * 1e6, "k-", lw=1, label="series solution, y = L/2")
    bx.plot(centre.time, probe * 1e6, "o", ms=3, label="SPH probe")
    bx.set_xlabel("t [s]")
    bx.set_ylabel("$v_x$ [$\\mu$m/s]")
    bx.set_title("centre-line velocity", fontsize=10)
    bx.legend(loc="lower right", fontsize=8)
    bx.grid(alpha=0.3)
    fig.suptitle("Poiseuille flow against Morris et al. (1997), L/dx = %.0f" % (L / dx))
    fig.tight_layout()
    print("Plot: " + sv.save(fig, "poiseuille2D.png"))


if __name__ == "__main__":
    main()
