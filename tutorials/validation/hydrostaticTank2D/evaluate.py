#!/usr/bin/env python3
"""hydrostaticTank2D: pressure against rho0 g (H - z) after settling, and the residual speed.

Reads postProcessing/{pressure,stats,level}, prints the figures as 'Figure: name = value'
lines (the first one is the case's error figure, read by spindriftBench) and draws
hydrostaticTank2D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).

Figures (time averages over the last quarter of the run, 'after settling'):
  bottomPressureError  |p - rho0 g (H - z)| / (rho0 g (H - z)) at the bottom probe (1.5 h
                       above the floor), in %
  midPressureError     the same at mid-depth (z = H/2), in %
  maxSpeed             largest particle speed at the end [m/s]
  levelError           free-surface level at the gauge minus H, in particle spacings
H is the column's initial height (exact by mass conservation: rho0 g H is the weight per area).
"""
import os
import re
import sys

import numpy as np


def read_dat(name, case="."):
    """Rows of postProcessing/<name>/<t>/<name>.dat over every start-time folder, in time order."""
    base = os.path.join(case, "postProcessing", name)
    folders = sorted(os.listdir(base), key=float)
    header, rows = None, []
    for f in folders:
        path = os.path.join(base, f, name + ".dat")
        with open(path) as fh:
            header = fh.readline().lstrip("#").split()
        data = np.genfromtxt(path, comments="#", ndmin=2)
        rows.append(data)
    return header, np.vstack(rows)


def dict_value(path, keyword):
    text = re.sub(r"//.*", "", open(path).read())
    m = re.search(r"\b" + keyword + r"\s+([^;]+);", text)
    return m.group(1).strip() if m else None


def vector(text):
    return [float(v) for v in text.strip("() ").split()]


def main():
    plot = "--no-plot" not in sys.argv and os.environ.get("SPINDRIFT_NO_PLOT", "0") != "1"
    rho0 = float(dict_value("constant/fluidProperties", "rho0"))
    g = abs(vector(dict_value("constant/fluidProperties", "gravity"))[1])
    dx = float(dict_value("constant/fluidProperties", "particleSpacing"))
    geometry = re.sub(r"//.*", "", open("constant/geometry").read())
    fluid = geometry[geometry.index("fluid"):]
    H = vector(re.search(r"max\s*(\([^)]*\))", fluid).group(1))[1]

    header, p = read_dat("pressure")
    t = p[:, 0]
    pcols = [i for i, c in enumerate(header) if c.startswith("p(")]
    z = np.array([float(header[i][2:-1].split(",")[1]) for i in pcols])
    end = t[-1]
    window = t >= 0.75 * end
    pmean = p[window][:, pcols].mean(axis=0)
    exact = rho0 * g * (H - z)
    rel = 100 * np.abs(pmean - exact) / exact
    bottom = int(np.argmin(z))
    mid = int(np.argmin(np.abs(z - H / 2)))

    sh, stats = read_dat("stats")
    speed = stats[:, sh.index("maxSpeed")]
    lh, level = read_dat("level")
    level_error = (level[level[:, 0] >= 0.75 * end][:, 1].mean() - H) / dx

    print("Figure: bottomPressureError = %.3f %% (probe z = %.4g m: %.1f Pa, exact %.1f Pa)"
          % (rel[bottom], z[bottom], pmean[bottom], exact[bottom]))
    print("Figure: midPressureError = %.3f %% (probe z = %.4g m: %.1f Pa, exact %.1f Pa)"
          % (rel[mid], z[mid], pmean[mid], exact[mid]))
    print("Figure: maxSpeed = %.4g m/s (at t = %g s)" % (speed[-1], stats[-1, 0]))
    print("Figure: levelError = %.3f particle spacings (surface %.4f m, H = %g m)"
          % (level_error, level[-1, 1], H))

    if not plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    for k, i in enumerate([pcols[bottom], pcols[mid]]):
        zz = z[[bottom, mid][k]]
        a.plot(t, p[:, i], lw=1, label="SPH, z = %.3g m" % zz)
        a.axhline(rho0 * g * (H - zz), ls="--", color="C%d" % k, lw=1, label="$\\rho_0 g (H - z)$, z = %.3g m" % zz)
    a.axvspan(0.75 * end, end, color="0.9", zorder=-1)
    a.set_xlabel("t [s]")
    a.set_ylabel("p [Pa]")
    a.set_title("probe pressure (averaging window shaded)")
    a.legend(fontsize=8)
    zz = np.linspace(0, H, 50)
    b.plot(rho0 * g * (H - zz), zz, "k-", label="$\\rho_0 g (H - z)$")
    b.plot(pmean, z, "o", label="SPH probes (time average)")
    b.set_xlabel("p [Pa]")
    b.set_ylabel("z [m]")
    b.set_title("bottom error %.2f %%, mid-depth %.2f %%" % (rel[bottom], rel[mid]))
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("hydrostaticTank2D.png", dpi=90)
    print("Plot: hydrostaticTank2D.png")


if __name__ == "__main__":
    main()
