#!/usr/bin/env python3
"""Wave height and period at the waterLevel gauges of a wave flume (tutorials waveTank2D,
oceanBreaking3D) against the wave maker's target, and where the waves break on a beach. Run it
in the case:

    python3 $SPINDRIFT_DIR/etc/python/checkWaves.py [--gauges 0 1] [--height-tolerance 0.05]
                                                    [--period-tolerance 0.01] [--reflector X]
                                                    [--breaking beach]

Reads the target (waveHeight, period, depth, rampTime) from constant/geometry, the piston's face
at rest (the max x of the wall named piston) and the gauges' levels from
postProcessing/gauges/0/gauges.dat. At each gauge x_g the waves are measured over
the window from the arrival of the fully ramped waves, (x_g - x_p)/c_g + rampTime + T (x_p the
piston's face, c_g the group velocity of linear theory), to the earliest return of a reflection
from the far end (--reflector, default the tank's end): (2 x_r - x_g - x_p)/c_g. In the window,
waves are cut at the zero up-crossings of the level less its mean; each whole wave gives a height
(crest less trough) and a period (between up-crossings, interpolated). Their means must be within
the tolerances of the target H and T (or, with --height-range, the height within that range of
H: a coarse quick mode); exit status 1 when not.

--breaking NAME reads the waterLevel function object NAME (gauges along a 2D beach, the wall
`polygon` named beach in constant/geometry) over the window from the ramped waves' arrival (the
group velocity integrated over the still depth) to the run's end, and prints the height along
the beach against linear shoaling (energy flux conserved, H sqrt(c_g) constant), the breaking
point (the gauge of largest height: H_b, its still depth h_b) against the breaker index
H_b/h_b (McCowan 1894: 0.78; Weggel 1972 for the slope: b - a H_b/(g T^2)) and Komar & Gaughan's
(1972) H_b = 0.39 g^(1/5) (T H0^2)^(2/5), and the height in the surf zone (half the breaking
depth) against h_b. It fails when no wave breaks before the shore: the largest height not
inside --breaking-index (default 0.6 1.3) of its depth, or the height half way from the
breaking point to the shore not below --surf-decay (default 0.7) of H_b.
"""
import argparse
import math
import re
import sys

import numpy as np


def keyword(text, name):
    m = re.search(r"\b" + name + r"\s+([-+0-9.eE]+)\s*;", text)
    if not m:
        sys.exit(f"constant/geometry: no '{name}'")
    return float(m.group(1))


def wave_number(omega, depth, g=9.81):
    k = max(omega * omega / g, omega / math.sqrt(g * depth))
    for _ in range(100):
        t = math.tanh(k * depth)
        k -= (g * k * t - omega * omega) / (g * (t + k * depth * (1 - t * t)))
    return k


def group_velocity(omega, depth):
    k = wave_number(omega, depth)
    kd = k * depth
    return 0.5 * omega / k * (1 + 2 * kd / math.sinh(2 * kd))


def waves(t, eta, t0, t1):
    """Heights and periods of the whole waves of eta(t) over t0 <= t <= t1, cut at the zero
    up-crossings of eta less its mean; None when the window holds (almost) no data."""
    w = (t >= t0) & (t <= t1)
    if w.sum() < 10:
        return None
    tw, ew = t[w], eta[w] - eta[w].mean()
    up = [i for i in range(len(ew) - 1) if ew[i] < 0 <= ew[i + 1]]
    crossings = [tw[i] + (tw[i + 1] - tw[i]) * (-ew[i]) / (ew[i + 1] - ew[i]) for i in up]
    heights = [float(np.ptp(ew[up[j]:up[j + 1] + 1])) for j in range(len(up) - 1)]
    periods = [crossings[j + 1] - crossings[j] for j in range(len(up) - 1)]
    return heights, periods, float(eta[w].mean())


def read_gauges(name):
    """Times, the gauges' x and their levels (one column a gauge) of postProcessing/<name>/0."""
    path = f"postProcessing/{name}/0/{name}.dat"
    with open(path) as f:
        header = f.readline().split("\t")[1:]
    xs = [float(re.search(r"\(([-+0-9.eE]+)", label).group(1)) for label in header]
    data = np.loadtxt(path, comments="#")
    return data[:, 0], xs, data[:, 1:], [label.strip() for label in header]


def beach_bed(geometry):
    """The bed's height under x of the 2D polygon wall named beach: its upper edges' height."""
    m = re.search(r"\bbeach\s*\{[^}]*?points\s*\(((?:\s*\([^)]*\))+)\s*\)", geometry)
    if not m:
        sys.exit("constant/geometry: no wall 'beach' of type polygon with its 'points'")
    pts = [tuple(float(v) for v in q.split()[:2]) for q in re.findall(r"\(([^)]*)\)", m.group(1))]

    def bed(x):
        ys = [0.0]
        for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
            if min(x0, x1) <= x <= max(x0, x1) and x0 != x1:
                ys.append(y0 + (y1 - y0) * (x - x0) / (x1 - x0))
        return max(ys)
    return bed


def breaking(a, H, T, d, ramp, geometry):
    """The waves along the beach (see the module's comment); True when they break as they should."""
    g = 9.81
    omega = 2 * math.pi / T
    bed = beach_bed(geometry)
    t, xs, levels, _ = read_gauges(a.breaking)
    # the ramped waves' arrival: the group velocity integrated over the still depth from the piston
    def arrival(x, n=400):
        s = np.linspace(a.piston_face, x, n)
        h = np.maximum([d - bed(v) for v in s], 0.02 * d)
        return ramp + T + float(np.trapz([1 / group_velocity(omega, v) for v in h], s))
    cg1 = group_velocity(omega, d)
    H0 = H * math.sqrt(cg1 / (0.5 * g * T / (2 * math.pi)))  # deep-water height of the target
    rows = []
    for j, x in enumerate(xs):
        h = d - bed(x)
        got = waves(t, levels[:, j] - d, arrival(x), t[-1]) if h > 0 else None
        if got and len(got[0]) >= a.min_waves:
            shoaled = H * math.sqrt(cg1 / group_velocity(omega, h))
            rows.append((x, h, float(np.mean(got[0])), shoaled, len(got[0]), got[2]))
    if len(rows) < 3:
        print(f"breaking: fewer than 3 gauges of '{a.breaking}' with {a.min_waves} whole waves (the run ends at {t[-1]:.2f} s)")
        return False
    print(f"along the beach ('{a.breaking}'), from the ramped waves' arrival to {t[-1]:.2f} s:")
    print("  x [m]   depth [m]  waves  H [m]    linear shoaling [m]  H/depth  mean level less d [m]")
    for x, h, Hm, Hs, n, setup in rows:
        print(f"  {x:6.2f}  {h:8.3f}  {n:5d}  {Hm:.4f}   {Hs:.4f} ({100 * (Hm / Hs - 1):+5.1f} %)   {Hm / h:6.3f}   {setup:+.4f}")
    ib = max(range(len(rows)), key=lambda i: rows[i][2])
    xb, hb, Hb = rows[ib][0], rows[ib][1], rows[ib][2]
    slope = (bed(xb + 0.1) - bed(xb - 0.1)) / 0.2
    wa, wb = 43.8 * (1 - math.exp(-19 * slope)), 1.56 / (1 + math.exp(-19.5 * slope))
    weggel = wb - wa * Hb / (g * T * T)
    komar = 0.39 * g ** 0.2 * (T * H0 * H0) ** 0.4
    print(f"breaking point (largest height): x {xb:.2f} m, depth h_b {hb:.3f} m, H_b {Hb:.4f} m; "
          f"H_b/h_b {Hb / hb:.3f} (McCowan 0.78, Weggel {weggel:.3f} for the slope 1:{1 / slope:.0f}); "
          f"H_b against Komar & Gaughan's {komar:.4f} m: {100 * (Hb / komar - 1):+.1f} %")
    ok = True
    lo, hi = a.breaking_index
    if not lo <= Hb / hb <= hi:
        print(f"  FAIL: H_b/h_b {Hb / hb:.3f} outside {lo}-{hi}: the waves do not break as waves do on a beach")
        ok = False
    surf = [r for r in rows if r[1] <= hb / 2]
    if not surf:
        print(f"  FAIL: no gauge with waves shoreward of half the breaking depth ({hb / 2:.3f} m)")
        return False
    xs_, hs_, Hs_ = surf[0][0], surf[0][1], surf[0][2]
    print(f"surf zone at x {xs_:.2f} m (depth {hs_:.3f} m, half h_b): H {Hs_:.4f} m = {Hs_ / Hb:.2f} H_b, "
          f"H/depth {Hs_ / hs_:.2f}")
    if Hs_ > a.surf_decay * Hb:
        print(f"  FAIL: the height in the surf zone is not below {a.surf_decay} H_b: the waves did not break")
        ok = False
    return ok


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--gauges", type=int, nargs="+", default=[0, 1])
    p.add_argument("--height-tolerance", type=float, default=0.05)
    p.add_argument("--period-tolerance", type=float, default=0.01)
    p.add_argument("--reflector", type=float, default=None, help="x of the far end [m]")
    p.add_argument("--piston-face", type=float, default=None,
                   help="x of the piston's face at rest [m] (default: the max x of the wall 'piston')")
    p.add_argument("--min-waves", type=int, default=2)
    p.add_argument("--height-range", type=float, nargs=2, metavar=("LO", "HI"),
                   help="accept a mean height from LO H to HI H instead of the tolerance (a coarse quick mode)")
    p.add_argument("--breaking", metavar="NAME",
                   help="the waterLevel function object of gauges along the beach: where the waves break")
    p.add_argument("--breaking-index", type=float, nargs=2, default=[0.6, 1.3], metavar=("LO", "HI"))
    p.add_argument("--surf-decay", type=float, default=0.7)
    a = p.parse_args()

    geometry = open("constant/geometry").read()
    H, T, d = keyword(geometry, "waveHeight"), keyword(geometry, "period"), keyword(geometry, "depth")
    ramp = keyword(geometry, "rampTime")
    reflector = a.reflector
    if reflector is None:  # the tank's end: the container's max x
        m = re.search(r"tank\s*\{[^}]*max\s*\(\s*([-+0-9.eE]+)", geometry)
        reflector = float(m.group(1))
    if a.piston_face is None:
        m = re.search(r"piston\s*\{[^}]*?max\s*\(\s*([-+0-9.eE]+)", geometry)
        if not m:
            sys.exit("constant/geometry: no wall 'piston' with a 'max': give --piston-face")
        a.piston_face = float(m.group(1))
    omega = 2 * math.pi / T
    k = wave_number(omega, d)
    kd = k * d
    cg = group_velocity(omega, d)
    print(f"target H {H} m, T {T} s in d {d} m: L {2 * math.pi / k:.4f} m, kd {kd:.4f}, c_g {cg:.4f} m/s")

    t, xs, levels, header = read_gauges("gauges")
    ok = True
    for g in a.gauges:
        label, xg = header[g], xs[g]
        t0 = (xg - a.piston_face) / cg + ramp + T
        t1 = (2 * reflector - xg - a.piston_face) / cg
        got = waves(t, levels[:, g], t0, min(t1, t[-1]))
        if got is None:
            print(f"gauge {label}: the window {t0:.2f}-{t1:.2f} s holds no data (run ends at {t[-1]:.2f} s)")
            ok = False
            continue
        heights, periods, mean_level = got
        if len(heights) < a.min_waves:
            print(f"gauge {label}: {len(heights)} whole waves in {t0:.2f}-{t1:.2f} s, fewer than {a.min_waves}")
            ok = False
            continue
        Hm, Tm = float(np.mean(heights)), float(np.mean(periods))
        eH, eT = Hm / H - 1, Tm / T - 1
        print(f"gauge {label}: {len(heights)} waves in {t0:.2f}-{t1:.2f} s: H {Hm:.4f} m ({100 * eH:+.1f} %, "
              f"each {' '.join(f'{h:.4f}' for h in heights)}), T {Tm:.4f} s ({100 * eT:+.2f} %), "
              f"mean level {mean_level:.4f} m")
        if a.height_range:
            if not a.height_range[0] <= Hm / H <= a.height_range[1]:
                print(f"  FAIL: wave height {Hm / H:.3f} H outside {a.height_range[0]}-{a.height_range[1]} H")
                ok = False
        elif abs(eH) > a.height_tolerance:
            print(f"  FAIL: wave height off the target by more than {100 * a.height_tolerance:.1f} %")
            ok = False
        if abs(eT) > a.period_tolerance:
            print(f"  FAIL: period off the target by more than {100 * a.period_tolerance:.1f} %")
            ok = False
    if a.breaking:
        ok = breaking(a, H, T, d, ramp, geometry) and ok
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
