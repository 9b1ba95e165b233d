#!/usr/bin/env python3
"""hydrostaticTank2D: pressure against rho0 g (H - z) after settling, and the residual speed.

Reads postProcessing/{pressure,stats,level}, prints the figures as 'Figure: name = value'
lines (the first one is the case's error figure, read by spindriftBench) and draws
hydrostaticTank2D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).

Figures (time averages over the last quarter of the run, 'after settling'):
  bottomPressureError  |p - rho0 g (H - z)| / (rho0 g (H - z)) at the bottom probe (1.5 h
                       above the floor), in %
  midPressureError     the same at mid-depth (z = H/2), in %
  bottomPressureNoise  the bottom probe's standard deviation over the window, in % of
                       rho0 g (H - z): still water's pressure should be still (an iterative
                       solver that stops short leaves its column ringing)
  maxSpeed             largest particle speed at the end [m/s]
  levelError           free-surface level at the gauge minus H, in particle spacings
H is the column's initial height (exact by mass conservation: rho0 g H is the weight per area).
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
    rho0, g, dx = props["rho0"], abs(props["gravity"][1]), props["particleSpacing"]
    H = sv.geometry_box("fluid")[1][1]

    p = sv.read_dat("pressure")
    t = p.time
    pcols = [i for i, c in enumerate(p.columns) if c.startswith("p(")]
    z = np.array([float(p.columns[i][2:-1].split(",")[1]) for i in pcols])
    end = t[-1]
    window = t >= 0.75 * end
    pmean = p.data[window][:, pcols].mean(axis=0)
    pstd = p.data[window][:, pcols].std(axis=0)
    exact = rho0 * g * (H - z)
    rel = 100 * np.abs(pmean - exact) / exact
    bottom = int(np.argmin(z))
    mid = int(np.argmin(np.abs(z - H / 2)))

    stats = sv.read_dat("stats")
    speed = stats["maxSpeed"]
    level = sv.read_dat("level")
    level_error = (level.data[level.time >= 0.75 * end][:, 1].mean() - H) / dx

    print("Figure: bottomPressureError = %.3f %% (probe z = %.4g m: %.1f Pa, exact %.1f Pa)"
          % (rel[bottom], z[bottom], pmean[bottom], exact[bottom]))
    print("Figure: midPressureError = %.3f %% (probe z = %.4g m: %.1f Pa, exact %.1f Pa)"
          % (rel[mid], z[mid], pmean[mid], exact[mid]))
    print("Figure: bottomPressureNoise = %.3f %% (standard deviation %.1f Pa over %d samples)"
          % (100 * pstd[bottom] / exact[bottom], pstd[bottom], int(window.sum())))
    print("Figure: maxSpeed = %.4g m/s (at t = %g s)" % (speed[-1], stats.time[-1]))
    print("Figure: levelError = %.3f particle spacings (surface %.4f m, H = %g m)"
          % (level_error, level.data[-1, 1], H))

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, probe in enumerate([bottom, mid]):
        a.plot(t, p.data[:, pcols[probe]], lw=1, label="SPH, z = %.3g m" % z[probe])
        a.axhline(exact[probe], ls="--", color="C%d" % k, lw=1, label="$\\rho_0 g (H - z)$, z = %.3g m" % z[probe])
    a.axvspan(0.75 * end, end, color="0.9", zorder=-1, label="averaging window")
    a.set_xlabel("t [s]")
    a.set_ylabel("p [Pa]")
    a.set_title("probe pressure against hydrostatic", fontsize=10)
    sv.legend_beside(a)
    zz = np.linspace(0, H, 50)
    b.plot(rho0 * g * (H - zz), zz, "k-", label="$\\rho_0 g (H - z)$")
    b.plot(pmean, z, "o", label="SPH probes (time average)")
    b.set_xlabel("p [Pa]")
    b.set_ylabel("z [m]")
    b.set_title("profile: bottom error %.2f %%, mid-depth %.2f %%" % (rel[bottom], rel[mid]), fontsize=10)
    b.legend(loc="upper right", fontsize=8)
    fig.suptitle("hydrostatic tank, H/dx = %.0f: pressure after settling" % (H / dx))
    fig.tight_layout()
    print("Plot: " + sv.save(fig, "hydrostaticTank2D.png"))


if __name__ == "__main__":
    main()
