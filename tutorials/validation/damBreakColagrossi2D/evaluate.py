#!/usr/bin/env python3
"""damBreakColagrossi2D: the 2D dam break of Colagrossi & Landrini (2003), H = 0.6 m.

Reads postProcessing/front (surgeFront) and postProcessing/wallPressure (probes on the far
wall), prints 'Figure: name = value' lines (the first is the case's figure, read by
spindriftBench) and draws damBreakColagrossi2D.png (unless --no-plot or SPINDRIFT_NO_PLOT=1).

Dimensionless: T = t sqrt(g/H), front x/H, pressure p/(rho0 g H), with H the column height and
the far wall's face x = L, both from constant/geometry.
Figures:
  wallArrival      T at which the front is first within one particle spacing of the far wall:
                   the first sample with front >= L - dx, the front being the centre of the
                   furthest fluid particle within H/4 of the floor with at least 3 neighbours
                   (surgeFront), interpolated linearly between the samples around the crossing.
                   A fluid particle touching the wall has its centre dx/2 from the face.
  pressureOnset    T at which the probe nearest y = 0.006 m (sensor P1 of De Courcy et al. 2024)
                   first reads p > 0.5 rho0 g H (linear between samples): the impact as a
                   pressure sensor sees it; De Courcy et al.'s P1 jumps at T = 2.36
  pressureNoise    standard deviation over 3 <= T <= 5 of p/(rho0 g H) minus its 5 ms running
                   mean (centred, over the samples within +-2.5 ms), at the wall probe nearest
                   y = 0.16H (issue 18's definition; oscillations slower than 5 ms stay out)
  pressureNoiseP4  the same at the probe nearest y = 0.16 m (= 0.267H; sensor P4 of De Courcy
                   et al. 2024)
  pressureErrorP1, pressureErrorP4  RMS over 3 <= T <= 5 of the 5 ms running mean of p/(rho0 g H)
                   at P1 (y = 6 mm) and P4 (y = 0.16 m) minus De Courcy et al.'s curve (their
                   digitised points averaged in bins of dT = 0.1, interpolated linearly)
  p1Early          mean p/(rho0 g H) at P1 over 2.8 <= T <= 3.0 (De Courcy et al.: p1EarlyRef)
  peakP1, peakP1Time  largest 5 ms running mean of p/(rho0 g H) at P1 over T <= 3.5, and its T
  wallPenetration  the furthest any fluid particle centre got beyond a wall face (floor, left or
                   far wall) over the run, in dx (fieldStats' bounding box; 0 if none did), and
                   lostParticles: the fluid particles the run lost
  p4Mean, p4MeanRef  mean p/(rho0 g H) at P4 (y = 0.16 m) over 3 <= T <= 5, and De Courcy et al.'s
                   (their binned curve averaged over the same window: 0.33)
  pressureOscillation  standard deviation over 5 <= T <= 6 of the 5 ms running mean of p/(rho0 g H)
                   about its 50 ms running mean, at the probe nearest y = 0.16H: an oscillation of
                   5-50 ms (issue 35's numerical oscillation of 20-26 steps; nan before T = 6)
  minPairDistance  the closest two fluid particles came over the run, in dx (fieldStats)
  maxDensityError  the largest compression (rho - rho0)/rho0 of the run, in % (the log's End line,
                   every step; else fieldStats' samples)
"""
import os
import re
import sys

import numpy as np

# etc/python/spindriftValidation.py, from $SPINDRIFT_DIR (exported by etc/RunFunctions) or this tree
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")) if d]
try:
    import spindriftValidation as sv
except ImportError as e:
    sys.exit("%s: %s: set SPINDRIFT_DIR to Spindrift's directory (source its etc/bashrc)" % (sys.argv[0], e))

NOISE_WINDOW = (3.0, 5.0)   # T; also the window of the pressure errors against the reference
OSCILLATION_WINDOW = (5.0, 6.0)   # T: pressureOscillation
SLOW_MEAN = 50e-3           # s, the running mean the oscillation is measured about
EARLY_WINDOW = (2.8, 3.0)   # T: p1Early, reached by the quick run (T <= 3)
ONSET = 0.5                 # p/(rho0 g H) at P1 that marks the impact (pressureOnset)
RUNNING_MEAN = 5e-3         # s, the width of the centred running mean
P1_HEIGHT, P4_HEIGHT = 0.006, 0.16   # m: sensors P1 and P4 of De Courcy et al. (2024) at H = 0.6 m


def probe_columns(table):
    """{y: column name} of the pressure columns 'p(x,y)'."""
    out = {}
    for name in table.columns[1:]:
        m = re.match(r"p\(([^,]+),([^,)]+)", name)
        if m:
            out[float(m.group(2))] = name
    return out


def nearest(columns, y):
    key = min(columns, key=lambda k: abs(k - y))
    return key, columns[key]


def noise(T, t, p, window):
    """Standard deviation of p minus its running mean over the samples with T in 'window';
    nan when the run ends before the window."""
    smooth = sv.running_mean(t, p, RUNNING_MEAN)
    inside = (T >= window[0]) & (T <= window[1])
    if T[-1] < window[0] or inside.sum() < 10:
        return np.nan, smooth
    return float(np.std((p - smooth)[inside])), smooth


def reference(name, column):
    """(T, p/rho g H) of a reference CSV of this directory, sorted by T; empty arrays if it is missing."""
    rows = sv.read_csv(name)
    T, p = np.array([float(r["T"]) for r in rows]), np.array([float(r[column]) for r in rows])
    order = np.argsort(T, kind="stable")
    return T[order], p[order]


def binned(T, p, width=0.1):
    """The digitised points averaged in bins of T (their scatter and repeated times averaged out):
    (bin centres, means) of the non-empty bins."""
    if T.size == 0:
        return T, p
    k = np.floor(T / width).astype(int)
    keys = np.unique(k)
    return (np.array([T[k == j].mean() for j in keys]), np.array([p[k == j].mean() for j in keys]))


def reference_error(T, smooth, ref, window):
    """RMS over the samples with T in 'window' of smooth minus the binned reference (nan when the
    run ends before the window or there is no reference)."""
    Tb, pb = binned(*ref)
    inside = (T >= window[0]) & (T <= window[1])
    if Tb.size == 0 or inside.sum() < 10 or T[-1] < window[1]:
        return np.nan
    return float(np.sqrt(np.mean((smooth[inside] - np.interp(T[inside], Tb, pb)) ** 2)))


def wall_penetration(L, dx):
    """(furthest a fluid particle centre got beyond the floor, the left wall or the far wall, in
    dx, >= 0; particles lost), from the fieldStats table 'stats'."""
    stats = sv.read_dat("stats")
    beyond = np.concatenate([-stats["xMin"], stats["xMax"] - L, -stats["yMin"]])
    lost = int(stats["nParticles"][0] - stats["nParticles"].min())
    return max(0.0, float(beyond.max())) / dx, lost


def max_density_error():
    """The largest compression of the run in %: the log's End line (every step), else fieldStats'."""
    for log in ("log.spindrift",):
        if os.path.exists(log):
            m = re.search(r"max density error ([0-9.eE+-]+)%", open(log).read())
            if m:
                return float(m.group(1))
    return max(0.0, float(sv.read_dat("stats")["rhoErrMax"].max()))  # fieldStats: in %


def main():
    props = sv.fluid_properties()
    g, dx, rho0 = abs(props["gravity"][1]), props["particleSpacing"], props["rho0"]
    lo, hi = sv.geometry_box("fluid")
    H = hi[1] - lo[1]
    wall_lo, wall_hi = sv.geometry_box("walls")
    L = wall_hi[0]
    scale_t = np.sqrt(g / H)

    front = sv.read_dat("front")
    T_front = front.time * scale_t
    arrival = sv.first_crossing(T_front, front["front"], L - dx)
    print("Figure: wallArrival = %.4f (T = t sqrt(g/H) at which the front is first within dx of the far wall"
          "; H/dx = %.0f; run ends at T = %.3g)" % (arrival, H / dx, T_front[-1]))

    probes = sv.read_dat("wallPressure")
    t = probes.time
    T = t * scale_t
    columns = probe_columns(probes)
    pg = rho0 * g * H
    y_noise, col_noise = nearest(columns, 0.16 * H)
    y_p4, col_p4 = nearest(columns, P4_HEIGHT)
    y_p1, col_p1 = nearest(columns, P1_HEIGHT)
    p_noise, p_p4, p_p1 = probes[col_noise] / pg, probes[col_p4] / pg, probes[col_p1] / pg
    # a probe with no fluid within its support writes nan: no fluid there, p = 0
    p_noise, p_p4, p_p1 = (np.nan_to_num(p, nan=0.0) for p in (p_noise, p_p4, p_p1))
    sigma, smooth_noise = noise(T, t, p_noise, NOISE_WINDOW)
    sigma_p4, smooth_p4 = noise(T, t, p_p4, NOISE_WINDOW)
    ends = "" if T[-1] >= NOISE_WINDOW[1] else "; the run ends at T = %.3g, %s" % (
        T[-1], "before the window" if T[-1] < NOISE_WINDOW[0] else "inside the window")
    print("Figure: pressureNoise = %.4f (std of p/rho0gH minus its 5 ms running mean, %g <= T <= %g, probe y = "
          "%.3f m = %.3fH%s)" % (sigma, NOISE_WINDOW[0], NOISE_WINDOW[1], y_noise, y_noise / H, ends))
    print("Figure: pressureNoiseP4 = %.4f (the same at y = %.3f m = %.3fH)" % (sigma_p4, y_p4, y_p4 / H))
    smooth_p1 = sv.running_mean(t, p_p1, RUNNING_MEAN)
    onset = sv.first_crossing(T, p_p1, ONSET)
    print("Figure: pressureOnset = %.4f (T at which p/rho0gH at y = %.3f m first exceeds %g; De Courcy et al. "
          "2024: 2.36)" % (onset, y_p1, ONSET))
    ref_p1 = reference("decourcy2024_P1.csv", "p")
    ref_p4 = reference("decourcy2024_P4.csv", "p")
    err_p1 = reference_error(T, smooth_p1, ref_p1, NOISE_WINDOW)
    err_p4 = reference_error(T, smooth_p4, ref_p4, NOISE_WINDOW)
    print("Figure: pressureErrorP1 = %.4f (RMS of the 5 ms running mean of p/rho0gH at y = %.3f m minus De Courcy "
          "et al. 2024, %g <= T <= %g)" % (err_p1, y_p1, NOISE_WINDOW[0], NOISE_WINDOW[1]))
    print("Figure: pressureErrorP4 = %.4f (the same at y = %.3f m)" % (err_p4, y_p4))
    in_early = (T >= EARLY_WINDOW[0]) & (T <= EARLY_WINDOW[1])
    p1_early = float(p_p1[in_early].mean()) if in_early.any() else np.nan
    Tb, pb = binned(*ref_p1)
    ref_early = (Tb >= EARLY_WINDOW[0]) & (Tb <= EARLY_WINDOW[1])
    p1_early_ref = float(np.interp(np.mean(EARLY_WINDOW), Tb, pb)) if ref_early.any() else np.nan
    print("Figure: p1Early = %.3f (mean p/rho0gH at y = %.3f m, %g <= T <= %g)" % (p1_early, y_p1, *EARLY_WINDOW))
    print("Figure: p1EarlyRef = %.3f (De Courcy et al. 2024 at T = %g)" % (p1_early_ref, np.mean(EARLY_WINDOW)))
    early = T <= 3.5
    k = int(np.argmax(np.where(early, smooth_p1, -np.inf)))
    print("Figure: peakP1 = %.3f (largest 5 ms running mean of p/rho0gH at y = %.3f m, T <= 3.5)" % (smooth_p1[k], y_p1))
    print("Figure: peakP1Time = %.3f" % T[k])
    penetration, lost = wall_penetration(L, dx)
    print("Figure: wallPenetration = %.3f (dx: the furthest a fluid particle centre got beyond a wall face)" % penetration)
    print("Figure: lostParticles = %d" % lost)
    inside = (T >= NOISE_WINDOW[0]) & (T <= NOISE_WINDOW[1])
    p4_mean = float(p_p4[inside].mean()) if T[-1] >= NOISE_WINDOW[1] else np.nan
    Tb4, pb4 = binned(*ref_p4)
    ref4 = (Tb4 >= NOISE_WINDOW[0]) & (Tb4 <= NOISE_WINDOW[1])
    p4_ref = float(pb4[ref4].mean()) if ref4.any() else np.nan
    print("Figure: p4Mean = %.3f (mean p/rho0gH at y = %.3f m, %g <= T <= %g)" % (p4_mean, y_p4, *NOISE_WINDOW))
    print("Figure: p4MeanRef = %.3f (De Courcy et al. 2024, the same window)" % p4_ref)
    slow = sv.running_mean(t, smooth_noise, SLOW_MEAN)
    inside = (T >= OSCILLATION_WINDOW[0]) & (T <= OSCILLATION_WINDOW[1])
    oscillation = float(np.std((smooth_noise - slow)[inside])) if T[-1] >= OSCILLATION_WINDOW[1] else np.nan
    print("Figure: pressureOscillation = %.4f (std of the 5 ms running mean of p/rho0gH about its 50 ms running "
          "mean, %g <= T <= %g, y = %.3f m)" % (oscillation, *OSCILLATION_WINDOW, y_noise))
    stats = sv.read_dat("stats")
    print("Figure: minPairDistance = %.3f (dx: the closest two fluid particles came, T <= %.3g)"
          % (float(np.nanmin(stats["minPairDistance"])) / dx, stats.time[-1] * scale_t))
    print("Figure: maxDensityError = %.3f (%%: the largest compression of the run)" % max_density_error())

    if not sv.plot_requested():
        return
    plt = sv.pyplot()
    fig, axes = plt.subplots(3, 1, figsize=(11, 11), sharex=False)
    end = max(T_front[-1], T[-1])

    ax = axes[0]
    ax.plot(T_front, front["front"] / H, "-", lw=1.5, label="Spindrift front (particle centre), H/dx = %.0f" % (H / dx))
    ax.axhline(L / H, color="k", lw=1, label="far wall, x = %.3gH" % (L / H))
    if np.isfinite(arrival):
        ax.axvline(arrival, color="C0", ls="--", lw=1, label="arrival (within dx of the wall), T = %.3f" % arrival)
    if np.isfinite(onset):
        ax.axvline(onset, color="C0", ls=":", lw=1,
                   label="Spindrift: p > %g ρ0gH at P1, T = %.3f" % (ONSET, onset))
    if ref_p1[0].size:
        ax.axvline(ref_p1[0][0], color="C3", ls=":", lw=1.5,
                   label="De Courcy et al. 2024 (δ-SPH, H/400): pressure onset at P1, T = %.2f" % ref_p1[0][0])
    ax.set_xlim(0, min(end, 4))
    ax.set_ylim(1.9, L / H + 0.15)
    ax.set_xlabel("$T = t\\sqrt{g/H}$")
    ax.set_ylabel("front $x/H$")
    ax.set_title("surge front: wall arrival T = %.3f" % arrival, fontsize=11)
    ax.grid(alpha=0.3)
    sv.legend_beside(ax)

    ax = axes[1]
    ax.plot(T, p_p1, "-", color="C0", lw=0.5, alpha=0.4, label="Spindrift, y = %.3f m" % y_p1)
    ax.plot(T, smooth_p1, "-", color="C0", lw=1.5, label="Spindrift, 5 ms running mean")
    if ref_p1[0].size:
        ax.plot(ref_p1[0], ref_p1[1], "-", color="C3", lw=1.2, label="De Courcy et al. 2024, P1 (y = 6 mm)")
    ax.set_xlim(2, max(end, 3))
    ax.set_ylim(-0.3, 4.2)
    ax.set_xlabel("$T = t\\sqrt{g/H}$")
    ax.set_ylabel("$p/\\rho_0 g H$")
    ax.set_title("far-wall pressure by the floor (P1)", fontsize=11)
    ax.grid(alpha=0.3)
    sv.legend_beside(ax)

    ax = axes[2]
    ax.axvspan(*NOISE_WINDOW, color="0.9", label="noise window")
    # both probes named in metres and in H: "0.16H" (0.096 m) and P4's "0.16 m" (0.27H) read alike
    ax.plot(T, p_noise, "-", color="C0", lw=0.5, alpha=0.5,
            label="Spindrift, y = %.3f m = %.2fH (issue 18's probe; noise %.3f)" % (y_noise, y_noise / H, sigma))
    ax.plot(T, smooth_noise, "-", color="C0", lw=1.5, label="  5 ms running mean")
    ax.plot(T, p_p4, "-", color="C2", lw=0.5, alpha=0.5,
            label="Spindrift at P4, y = %.3f m = %.2fH (noise %.3f)" % (y_p4, y_p4 / H, sigma_p4))
    ax.plot(T, smooth_p4, "-", color="C2", lw=1.5, label="  5 ms running mean")
    if ref_p4[0].size:
        ax.plot(ref_p4[0], ref_p4[1], "-", color="C3", lw=1.2,
                label="De Courcy et al. 2024, P4 (y = 0.160 m = %.2fH)" % (P4_HEIGHT / H))
    ax.set_xlim(2, max(end, 3))
    ax.set_ylim(-0.3, 2.0)
    ax.set_xlabel("$T = t\\sqrt{g/H}$")
    ax.set_ylabel("$p/\\rho_0 g H$")
    ax.set_title("far-wall pressure higher up: noise = std(p − running mean), %g ≤ T ≤ %g" % NOISE_WINDOW,
                 fontsize=11)
    ax.grid(alpha=0.3)
    sv.legend_beside(ax)
    fig.tight_layout()
    print("Plot: " + sv.save(fig, "damBreakColagrossi2D.png"))


if __name__ == "__main__":
    main()
