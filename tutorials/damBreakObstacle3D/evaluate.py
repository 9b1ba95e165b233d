#!/usr/bin/env python3
"""damBreakObstacle3D: SPHERIC benchmark 2 (Kleefsman et al. 2005) against the MARIN experiment.

Reads postProcessing/heights (waterLevel at H1-H4), postProcessing/sensors (probes at P1-P8)
and postProcessing/stats (fieldStats), compares with kleefsman2005_experiment.csv (the
experiment's traces, thinned), prints 'Figure: name = value' lines and draws
damBreakObstacle3D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).

Figures (over 0 <= t <= min(6 s, the run's end); the simulation's samples interpolated linearly
to the experiment's times):
  rmsH1 ... rmsH4      RMS of the water height minus the experiment's, m
  rmsP1, rmsP3, rmsP5, rmsP7   RMS of the pressure minus the experiment's, Pa (the simulation's
                       pressure as its probe writes it: a probe with no fluid near it, nan, is 0);
                       rmsP1Mean ...: the same for the simulation's 5 ms running mean (the weakly
                       compressible impact rings in spikes of ~rho0 c0 u, tens of kPa, ~1 ms)
  peakH2, peakH2Exp    the largest H2 over 0 <= t <= 6 s (or the run's end), m; peakH2Error its
                       error in % of the experiment's (the bore coming back from the x = 0 wall,
                       0.341 m at 1.79 s in the experiment)
  peakH4, peakH4Exp    the largest H4 over 2 s <= t <= 6 s (or the run's end; the wave back into the
                       reservoir, 0.401 m at 3.84 s in the experiment; H4's largest value overall is its
                       start, 0.55 m), peakH4Error in %
  p1Onset, p1OnsetExp  the first time P1 exceeds 2000 Pa (about 0.4 rho0 g 0.55 m; linear between
                       samples): the water's arrival at the box as its sensor sees it (0.395 s)
  p1PeakTime, p1PeakTimeExp  the time of the largest 5 ms running mean of P1 within 0.1 s of its
                       onset: the impact peak (0.415 s in the experiment)
  p1PeakTimeError      p1PeakTime - p1PeakTimeExp, s (target: within 0.05 s)
  h4FallRMS            RMS over 0 <= t <= 0.6 s of H4 minus the experiment's, m: the reservoir
                       draining (the quick test's window)
  wallPenetration      the furthest any fluid particle centre got beyond the tank's floor or walls
                       over the run, in dx (fieldStats' bounding box; at rest a centre is dx/2
                       inside a face), and lostParticles: the fluid particles the run lost
  frontMin             the smallest x a fluid particle reached, m (the box's impacted face is at
                       x = 0.8245 m: the water passed the box when frontMin is below it)
"""
import os
import sys

import numpy as np

# etc/python/spindriftValidation.py, from $SPINDRIFT_DIR (exported by etc/RunFunctions) or this tree
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..")) if d]
try:
    import spindriftValidation as sv
except ImportError as e:
    sys.exit("%s: %s: set SPINDRIFT_DIR to Spindrift's directory (source its etc/bashrc)" % (sys.argv[0], e))

HERE = os.path.dirname(os.path.abspath(__file__))
WINDOW = (0.0, 6.0)
ONSET = 2000.0            # Pa: P1's arrival
RUNNING_MEAN = 5e-3       # s
H4_FALL = (0.0, 0.6)      # s
H2_PEAK = (0.0, 6.0)      # s (the experiment's: the bore back from the x = 0 wall, 0.341 m at 1.79 s)
H4_RETURN = (2.0, 6.0)    # s
BOX_FACE_X = 0.8245


def experiment():
    with open(os.path.join(HERE, "kleefsman2005_experiment.csv")) as fh:
        lines = [line for line in fh if not line.startswith("#")]
    names = lines[0].strip().split(",")
    rows = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: rows[:, k] for k, name in enumerate(names)}


def impact(t, p):
    """(onset, peak time) of a pressure trace: the first crossing of ONSET and the largest 5 ms
    running mean within 0.1 s after it."""
    onset = sv.first_crossing(t, p, ONSET)
    if not np.isfinite(onset):
        return np.nan, np.nan
    smooth = sv.running_mean(t, p, RUNNING_MEAN)
    near = (t >= onset - 0.01) & (t <= onset + 0.1)
    return onset, float(t[near][np.argmax(smooth[near])])


def main():
    exp = experiment()
    props = sv.fluid_properties()
    dx = props["particleSpacing"]
    tank_lo, tank_hi = sv.geometry_box("walls")

    heights = sv.read_dat("heights")
    sensors = sv.read_dat("sensors")
    t_end = min(heights.time[-1], sensors.time[-1])
    window = (WINDOW[0], min(WINDOW[1], t_end))
    te = exp["t"]
    inside = (te >= window[0]) & (te <= window[1])
    print("damBreakObstacle3D: dx = 0.55/%.4g m, run to %.4g s, compared over %.3g-%.3g s"
          % (0.55 / dx, t_end, window[0], window[1]))

    sim = {}
    for k, name in enumerate(("H1", "H2", "H3", "H4")):
        sim[name] = (heights.time, heights.data[:, 1 + k])
    for k in range(8):
        p = np.nan_to_num(sensors.data[:, 1 + k], nan=0.0)
        sim["P%d" % (k + 1)] = (sensors.time, p)

    def on_exp(name, mask):
        t, y = sim[name]
        return np.interp(te[mask], t, y)

    figures = []
    for name, unit in (("H1", "m"), ("H2", "m"), ("H3", "m"), ("H4", "m"),
                       ("P1", "Pa"), ("P3", "Pa"), ("P5", "Pa"), ("P7", "Pa")):
        rms = float(np.sqrt(np.mean((on_exp(name, inside) - exp[name][inside]) ** 2)))
        scale = float(np.max(np.abs(exp[name][inside])))
        figures.append(("rms" + name, rms, "%s; %.1f %% of the experiment's largest |%s| %.4g %s over the window"
                        % (unit, 100 * rms / scale, name, scale, unit)))
        if name[0] == "P":  # the same of the simulation's 5 ms running mean: without the acoustic spikes
            t, y = sim[name]
            smooth = np.interp(te[inside], t, sv.running_mean(t, y, RUNNING_MEAN))
            rms = float(np.sqrt(np.mean((smooth - exp[name][inside]) ** 2)))
            figures.append(("rms%sMean" % name, rms, "Pa; %.1f %% (the simulation's 5 ms running mean)"
                            % (100 * rms / scale)))

    def peak(name, lo, hi):
        """(value, time) of the largest sample of the simulation and of the experiment over
        lo <= t <= min(hi, the run's end); nan if the run ends before lo."""
        hi = min(hi, window[1])
        t, y = sim[name]
        m, me = (t >= lo) & (t <= hi), (te >= lo) & (te <= hi)
        if hi <= lo or m.sum() == 0:
            return np.nan, np.nan, np.nan, np.nan, hi
        k, ke = np.argmax(y[m]), np.argmax(exp[name][me])
        return float(y[m][k]), float(t[m][k]), float(exp[name][me][ke]), float(te[me][ke]), hi

    for name, (lo, hi) in (("H2", H2_PEAK), ("H4", H4_RETURN)):
        v, tv, ve, tve, hi = peak(name, lo, hi)
        figures.append(("peak" + name, v, "m at t = %.3f s (largest %s over %g-%.3g s)" % (tv, name, lo, hi)))
        figures.append(("peak%sExp" % name, ve, "m at t = %.3f s (the experiment's)" % tve))
        figures.append(("peak%sError" % name, 100 * (v - ve) / ve, "% of the experiment's peak (target within 10 %)"))

    t1, p1 = sim["P1"]
    onset, peak_time = impact(t1, p1)
    onset_e, peak_time_e = impact(te, exp["P1"])
    figures.append(("p1Onset", onset, "s (P1 first above %g Pa)" % ONSET))
    figures.append(("p1OnsetExp", onset_e, "s (the experiment's)"))
    figures.append(("p1PeakTime", peak_time, "s (largest 5 ms mean of P1 within 0.1 s of the onset)"))
    figures.append(("p1PeakTimeExp", peak_time_e, "s (the experiment's)"))
    figures.append(("p1PeakTimeError", peak_time - peak_time_e, "s (target within 0.05 s)"))
    fall = (te >= H4_FALL[0]) & (te <= min(H4_FALL[1], window[1]))
    h4fall = float(np.sqrt(np.mean((on_exp("H4", fall) - exp["H4"][fall]) ** 2))) if window[1] >= H4_FALL[1] else np.nan
    figures.append(("h4FallRMS", h4fall, "m (H4 against the experiment over %g-%g s)" % H4_FALL))

    stats = sv.read_dat("stats")
    beyond = np.concatenate([tank_lo[0] - stats["xMin"], stats["xMax"] - tank_hi[0], tank_lo[1] - stats["yMin"],
                             stats["yMax"] - tank_hi[1], tank_lo[2] - stats["zMin"]])
    figures.append(("wallPenetration", max(0.0, float(beyond.max())) / dx,
                    "dx (the furthest a fluid particle centre got beyond the tank's floor or walls)"))
    figures.append(("lostParticles", int(stats["nParticles"][0] - stats["nParticles"].min()), "fluid particles"))
    figures.append(("frontMin", float(stats["xMin"].min()), "m (smallest x of the fluid; box face x = %g)" % BOX_FACE_X))
    for name, value, note in figures:
        print("Figure: %s = %s %s" % (name, ("%.4g" % value) if isinstance(value, float) else value, note))

    if sv.plot_requested():
        plot(exp, sim, window, dx)


def plot(exp, sim, window, dx):
    plt = sv.pyplot()
    fig, axes = plt.subplots(4, 2, figsize=(11, 11), sharex=True)
    names = ("H1", "P1", "H2", "P3", "H3", "P5", "H4", "P7")
    for ax, name in zip(axes.ravel(), names):
        m = (exp["t"] <= window[1])
        ax.plot(exp["t"][m], exp[name][m], color="0.4", lw=0.8, label="experiment (Kleefsman et al. 2005)")
        t, y = sim[name]
        s = t <= window[1]
        ax.plot(t[s], y[s], color="C0", lw=0.9, label="Spindrift, dx = 0.55/%.0f m" % (0.55 / dx))
        ax.set_ylabel(name + (" [m]" if name[0] == "H" else " [Pa]"))
        if name[0] == "P":  # the impact's acoustic spikes (tens of kPa, ~1 ms) clipped
            top = 1.6 * float(np.max(exp[name][m]))
            ax.set_ylim(-0.1 * top, top)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    sv.legend_below(fig, axes[-1])
    fig.suptitle("damBreakObstacle3D: SPHERIC benchmark 2, water heights H1-H4 and pressures P1, P3, P5, P7")
    sv.save(fig, "damBreakObstacle3D.png")
    print("wrote damBreakObstacle3D.png")


if __name__ == "__main__":
    main()
