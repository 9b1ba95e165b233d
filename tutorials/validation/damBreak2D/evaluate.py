#!/usr/bin/env python3
"""damBreak2D: surge front against Martin & Moyce (1952), column n^2 = 2.

Reads postProcessing/front, prints 'Figure: name = value' lines (the first is the case's error
figure, read by spindriftBench) and draws damBreak2D.png (unless --no-plot or
SPINDRIFT_NO_PLOT=1).

Dimensionless as in the experiment: T = n t sqrt(g/a), Z = front / a, with a the column width
(from constant/geometry), n = sqrt(2), the front measured from the column's back wall (x = 0).
The front is the furthest particle centre near the floor plus half a particle spacing (the
fluid's edge).
Figures:
  frontRMS     RMS of Z_SPH(T) - Z_exp over the experiment's points with T <= 3 (Z_SPH
               interpolated linearly in time)
  frontMaxDev  the largest |Z_SPH - Z_exp| over the same points
  frontShift   the time shift dT (in T) that brings the SPH front closest to the experiment's
               points, Z_SPH(T - dT) against Z_exp(T) (searched over -0.5..1 in steps of 0.005):
               how much the run leads the experiment, whose front starts late (its release)
  frontShapeRMS  the RMS of Z_SPH(T - dT) - Z_exp at that shift: the front's course with the
               start's lead taken out (it converges with resolution where frontRMS does not:
               docs/VALIDATION.md, "Why the front leads the experiment")
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
    g, dx = abs(props["gravity"][1]), props["particleSpacing"]
    lo, hi = sv.geometry_box("fluid")
    a = hi[0] - lo[0]
    n = np.sqrt((hi[1] - lo[1]) / a)  # column height n^2 a

    front = sv.read_dat("front")
    T = n * front.time * np.sqrt(g / a)
    Z = (front["front"] + 0.5 * dx) / a

    experiment = [row for row in sv.read_csv("martin_moyce_1952.csv") if row["series"] == "n2=2"]
    exp_T = np.array([float(row["T"]) for row in experiment])
    exp_Z = np.array([float(row["Z"]) for row in experiment])
    used = (exp_T <= 3) & (exp_T <= T[-1])
    if not used.any():
        sys.exit("the run ends at T = %.3g, before the first experimental point" % T[-1])
    def deviation(shift):  # Z_SPH(T - shift) - Z_exp(T) at the experiment's points
        return np.interp(exp_T[used] - shift, T, Z) - exp_Z[used]

    dev = deviation(0)
    rms = np.sqrt(np.mean(dev ** 2))
    print("Figure: frontRMS = %.4f (RMS of Z over %d experimental points with T <= 3; run ends at T = %.3g)"
          % (rms, used.sum(), T[-1]))
    print("Figure: frontMaxDev = %.4f" % np.max(np.abs(dev)))
    shifts = np.arange(-0.5, 1.0 + 1e-9, 0.005)
    shapeRms = [np.sqrt(np.mean(deviation(s) ** 2)) for s in shifts]
    best = int(np.argmin(shapeRms))
    shift = shifts[best]
    print("Figure: frontShift = %.3f (the run leads the experiment by t = %.1f ms)"
          % (shift, 1e3 * shift / (n * np.sqrt(g / a))))
    print("Figure: frontShapeRMS = %.4f (RMS of Z at that shift)" % shapeRms[best])

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(T, Z, "-", lw=1.5, label="Spindrift (a/dx = %.0f)" % (a / dx))
    ax.plot(T + shift, Z, "--", lw=1, color="0.4",
            label="the same, %.3f later (RMS %.3f)" % (shift, shapeRms[best]))
    ax.plot(exp_T, exp_Z, "ks", ms=5, mfc="none", label="Martin & Moyce (1952), $n^2 = 2$")
    ax.axvline(3, color="0.6", ls=":", lw=1, label="end of the RMS window, T = 3")
    ax.set_xlabel("$T = n t \\sqrt{g/a}$ [-] (a = column width, $n^2$ = height / a)")
    ax.set_ylabel("$Z$ = surge front / a [-]")
    ax.set_title("dam-break surge front against experiment: RMS(Z, T $\\leq$ 3) = %.3f" % rms, fontsize=11)
    ax.set_xlim(0, max(3.5, T[-1]))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    print("Plot: " + sv.save(fig, "damBreak2D.png"))


if __name__ == "__main__":
    main()
