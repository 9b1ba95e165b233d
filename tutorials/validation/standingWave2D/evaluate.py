#!/usr/bin/env python3
"""standingWave2D: a linear standing wave's period and the height it loses a period.

Reads postProcessing/gauges (waterLevel at both end walls, the antinodes), prints the figures as
'Figure: name = value' lines (the first one is the case's error figure, read by spindriftBench)
and draws standingWave2D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).

The antinodes move in opposite phase: eta = (level_left - level_right)/2 = a e^(-b t) sin(omega t)
(linear theory: omega^2 = g k tanh(k d), k = pi/L; the damping at water's viscosity is below 0.1 %
a period). Its extremes, one each half period, give the envelope, fitted by an exponential.

Figures:
  dampingPerPeriod  amplitude lost a period, 1 - e^(-b T), in % (physically ~0)
  periodError       mean period between the extremes against linear theory's, in %
  firstAmplitude    the first extreme against a, in %
"""
import math
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

AMPLITUDE = 0.05  # m, constant/geometry's velocity field


def main():
    props = sv.fluid_properties()
    g = abs(props["gravity"][1])
    lo, hi = sv.geometry_box("fluid")
    L, d = hi[0] - lo[0], hi[1] - lo[1]
    k = math.pi / L
    omega = math.sqrt(g * k * math.tanh(k * d))
    T = 2 * math.pi / omega
    gauges = sv.read_dat("gauges")
    t = gauges.time
    eta = (gauges.data[:, 1] - gauges.data[:, 2]) / 2
    extremes = []
    for i in range(int(t[-1] / (T / 2))):  # the extreme of half period i, near T/4 + i T/2
        m = np.abs(t - (T / 4 + i * T / 2)) < T / 8
        if m.any():
            j = np.argmax(np.abs(eta[m]))
            extremes.append((t[m][j], abs(eta[m][j])))
    if len(extremes) < 3:
        sys.exit("evaluate.py: fewer than 3 half periods written (run to %g s at least)" % (1.5 * T))
    ext = np.array(extremes)
    slope = np.polyfit(ext[:, 0], np.log(ext[:, 1]), 1)[0]
    damping = 100 * (1 - math.exp(slope * T))
    period = 2 * (ext[-1, 0] - ext[0, 0]) / (len(ext) - 1)
    print("Figure: dampingPerPeriod = %.2f %% (amplitude lost a period, %d half periods, amplitudes %s m)"
          % (damping, len(ext), " ".join("%.4f" % a for a in ext[:, 1])))
    print("Figure: periodError = %.2f %% (%.4f s against linear theory's %.4f s)" % (100 * (period / T - 1), period, T))
    print("Figure: firstAmplitude = %.1f %% of a = %g m" % (100 * ext[0, 1] / AMPLITUDE, AMPLITUDE))

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, a = plt.subplots(figsize=(9, 4))
    a.plot(t, eta, lw=1, label="SPH, (level left - level right)/2")
    tt = np.linspace(0, t[-1], 400)
    a.plot(tt, AMPLITUDE * np.sin(omega * tt), "k--", lw=0.8, label="linear theory, undamped")
    a.plot(ext[:, 0], ext[:, 1], "o", ms=4, label="extremes (envelope)")
    a.set_xlabel("t [s]")
    a.set_ylabel("surface at the antinodes [m]")
    a.set_title("standing wave, d = %g m, L = %g m: %.1f %% of the height lost a period" % (d, L, damping), fontsize=10)
    sv.legend_beside(a)
    fig.tight_layout()
    print("Plot: " + sv.save(fig, "standingWave2D.png"))


if __name__ == "__main__":
    main()
