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
import re
import sys

import numpy as np


def read_dat(name, case="."):
    base = os.path.join(case, "postProcessing", name)
    header, rows = None, []
    for f in sorted(os.listdir(base), key=float):
        path = os.path.join(base, f, name + ".dat")
        with open(path) as fh:
            header = fh.readline().lstrip("#").split()
        rows.append(np.genfromtxt(path, comments="#", ndmin=2))
    return header, np.vstack(rows)


def read_vtp(path):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    out = reader.GetOutput()
    return vtk_to_numpy(out.GetPoints().GetData()), vtk_to_numpy(out.GetPointData().GetArray("velocity"))


def times(case="."):
    out = []
    for d in os.listdir(case):
        try:
            t = float(d)
        except ValueError:
            continue
        if os.path.exists(os.path.join(case, d, "fluid.vtp")):
            out.append((t, d))
    return sorted(out)


def dict_value(path, keyword):
    text = re.sub(r"//.*", "", open(path).read())
    m = re.search(r"\b" + keyword + r"\s+([^;]+);", text)
    return m.group(1).strip() if m else None


def vector(text):
    return [float(v) for v in text.strip("() ").split()]


def exact(y, t, F, nu, L):
    v = F / (2 * nu) * y * (L - y)
    for n in range(200):
        k = 2 * n + 1
        v = v - 4 * F * L ** 2 / (nu * np.pi ** 3 * k ** 3) * np.sin(k * np.pi * y / L) * np.exp(-k * k * np.pi ** 2 * nu * t / L ** 2)
    return v


def main():
    plot = "--no-plot" not in sys.argv and os.environ.get("SPINDRIFT_NO_PLOT", "0") != "1"
    F = vector(dict_value("constant/fluidProperties", "gravity"))[0]
    nu = float(dict_value("constant/fluidProperties", "viscosity"))
    geometry = re.sub(r"//.*", "", open("constant/geometry").read())
    fluid = geometry[geometry.index("fluid"):]
    L = vector(re.search(r"max\s*(\([^)]*\))", fluid).group(1))[1]

    written = times()
    end = written[-1][0]
    checks = [c for c in (0.0225, 0.045, 0.1125, 0.225) if c < end - 1e-9] + [end]
    results = []
    for tc in checks:
        t, d = min(written, key=lambda w: abs(w[0] - tc))
        x, u = read_vtp(os.path.join(d, "fluid.vtp"))
        ue = exact(x[:, 1], t, F, nu, L)
        results.append((t, np.sqrt(np.sum((u[:, 0] - ue) ** 2) / np.sum(ue ** 2)), x[:, 1], u[:, 0]))
    l2 = max(r[1] for r in results)
    header, centre = read_dat("centre")
    uc, tc = centre[-1, header.index("Ux(0.00025,0.0005)")], centre[-1, 0]
    uce = exact(np.array(L / 2), tc, F, nu, L)
    print("Figure: velocityL2 = %.4f (largest relative L2 error over the particles at t = %s s)"
          % (l2, ", ".join("%.4g" % r[0] for r in results)))
    for t, e, _, _ in results:
        print("    t = %.4g s: L2 = %.4f" % (t, e))
    print("Figure: centreError = %.4f (centre-line probe %.4g m/s, exact %.4g m/s at t = %.3g s)"
          % ((uc - uce) / uce, uc, uce, tc))

    if not plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.6))
    yy = np.linspace(0, L, 200)
    for j, (t, e, y, u) in enumerate(results):
        ax.plot(exact(yy, t, F, nu, L) * 1e6, yy * 1e3, "-", color="C%d" % j, lw=1)
        ax.plot(u * 1e6, y * 1e3, ".", color="C%d" % j, ms=3, label="t = %.4g s (L2 %.3f)" % (t, e))
    ax.set_xlabel("$v_x$ [$\\mu$m/s]")
    ax.set_ylabel("y [mm]")
    ax.set_title("particles (dots) against the series solution (lines)", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    tt = np.linspace(0, centre[-1, 0], 200)
    bx.plot(tt, exact(np.array(L / 2), tt, F, nu, L) * 1e6, "k-", lw=1, label="exact, y = L/2")
    bx.plot(centre[:, 0], centre[:, header.index("Ux(0.00025,0.0005)")] * 1e6, "o", ms=3, label="SPH probe")
    bx.set_xlabel("t [s]")
    bx.set_ylabel("$v_x$ [$\\mu$m/s]")
    bx.set_title("centre-line velocity", fontsize=10)
    bx.legend(fontsize=8)
    bx.grid(alpha=0.3)
    fig.suptitle("Poiseuille flow (Morris et al. 1997), L/dx = %.0f" % (L / float(dict_value("constant/fluidProperties", "particleSpacing"))))
    fig.tight_layout()
    fig.savefig("poiseuille2D.png", dpi=90)
    print("Plot: poiseuille2D.png")


if __name__ == "__main__":
    main()
