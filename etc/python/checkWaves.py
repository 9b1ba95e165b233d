#!/usr/bin/env python3
"""Wave height and period at the waterLevel gauges of a wave flume (tutorials waveTank2D,
oceanBreaking3D) against the wave maker's target. Run it in the case:

    python3 $SPINDRIFT_DIR/etc/python/checkWaves.py [--gauges 0 1] [--height-tolerance 0.05]
                                                    [--period-tolerance 0.01] [--reflector X]

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
    cg = 0.5 * omega / k * (1 + 2 * kd / math.sinh(2 * kd))
    print(f"target H {H} m, T {T} s in d {d} m: L {2 * math.pi / k:.4f} m, kd {kd:.4f}, c_g {cg:.4f} m/s")

    with open("postProcessing/gauges/0/gauges.dat") as f:
        header = f.readline().split("\t")[1:]
    data = np.loadtxt("postProcessing/gauges/0/gauges.dat", comments="#")
    t = data[:, 0]
    ok = True
    for g in a.gauges:
        label = header[g].strip()
        xg = float(re.search(r"\(([-+0-9.eE]+)", label).group(1))
        eta = data[:, 1 + g]
        t0 = (xg - a.piston_face) / cg + ramp + T
        t1 = (2 * reflector - xg - a.piston_face) / cg
        w = (t >= t0) & (t <= min(t1, t[-1]))
        if w.sum() < 10:
            print(f"gauge {label}: the window {t0:.2f}-{t1:.2f} s holds no data (run ends at {t[-1]:.2f} s)")
            ok = False
            continue
        tw, ew = t[w], eta[w] - eta[w].mean()
        up = [i for i in range(len(ew) - 1) if ew[i] < 0 <= ew[i + 1]]
        crossings = [tw[i] + (tw[i + 1] - tw[i]) * (-ew[i]) / (ew[i + 1] - ew[i]) for i in up]
        heights, periods = [], []
        for j in range(len(up) - 1):
            seg = ew[up[j]:up[j + 1] + 1]
            heights.append(seg.max() - seg.min())
            periods.append(crossings[j + 1] - crossings[j])
        if len(heights) < a.min_waves:
            print(f"gauge {label}: {len(heights)} whole waves in {t0:.2f}-{t1:.2f} s, fewer than {a.min_waves}")
            ok = False
            continue
        Hm, Tm = float(np.mean(heights)), float(np.mean(periods))
        eH, eT = Hm / H - 1, Tm / T - 1
        print(f"gauge {label}: {len(heights)} waves in {t0:.2f}-{t1:.2f} s: H {Hm:.4f} m ({100 * eH:+.1f} %, "
              f"each {' '.join(f'{h:.4f}' for h in heights)}), T {Tm:.4f} s ({100 * eT:+.2f} %), "
              f"mean level {eta[w].mean():.4f} m")
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
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
