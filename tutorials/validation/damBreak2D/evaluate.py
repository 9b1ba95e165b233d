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
"""
import csv
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


def dict_value(path, keyword):
    text = re.sub(r"//.*", "", open(path).read())
    m = re.search(r"\b" + keyword + r"\s+([^;]+);", text)
    return m.group(1).strip() if m else None


def vector(text):
    return [float(v) for v in text.strip("() ").split()]


def main():
    plot = "--no-plot" not in sys.argv and os.environ.get("SPINDRIFT_NO_PLOT", "0") != "1"
    g = abs(vector(dict_value("constant/fluidProperties", "gravity"))[1])
    dx = float(dict_value("constant/fluidProperties", "particleSpacing"))
    geometry = re.sub(r"//.*", "", open("constant/geometry").read())
    fluid = geometry[geometry.index("fluid"):]
    lo = vector(re.search(r"min\s*(\([^)]*\))", fluid).group(1))
    hi = vector(re.search(r"max\s*(\([^)]*\))", fluid).group(1))
    a = hi[0] - lo[0]
    n = np.sqrt((hi[1] - lo[1]) / a)  # column height n^2 a

    header, front = read_dat("front")
    t = front[:, 0]
    T = n * t * np.sqrt(g / a)
    Z = (front[:, header.index("front")] + 0.5 * dx) / a

    exp_T, exp_Z = [], []
    with open("martin_moyce_1952.csv") as fh:
        for row in csv.DictReader(line for line in fh if not line.startswith("#")):
            if row["series"] == "n2=2":
                exp_T.append(float(row["T"]))
                exp_Z.append(float(row["Z"]))
    exp_T, exp_Z = np.array(exp_T), np.array(exp_Z)
    used = (exp_T <= 3) & (exp_T <= T[-1])
    if not used.any():
        sys.exit("the run ends at T = %.3g, before the first experimental point" % T[-1])
    dev = np.interp(exp_T[used], T, Z) - exp_Z[used]
    rms = np.sqrt(np.mean(dev ** 2))
    print("Figure: frontRMS = %.4f (RMS of Z over %d experimental points with T <= 3; run ends at T = %.3g)"
          % (rms, used.sum(), T[-1]))
    print("Figure: frontMaxDev = %.4f" % np.max(np.abs(dev)))

    if not plot:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(T, Z, "-", lw=1.5, label="Spindrift (a/dx = %.0f)" % (a / dx))
    ax.plot(exp_T, exp_Z, "ks", ms=5, mfc="none", label="Martin & Moyce (1952), $n^2 = 2$")
    ax.axvline(3, color="0.6", ls=":", lw=1)
    ax.set_xlabel("$T = n t \\sqrt{g/a}$")
    ax.set_ylabel("$Z$ = front / a")
    ax.set_title("dam-break surge front: RMS(Z, T $\\leq$ 3) = %.3f" % rms)
    ax.set_xlim(0, max(3.5, T[-1]))
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig("damBreak2D.png", dpi=90)
    print("Plot: damBreak2D.png")


if __name__ == "__main__":
    main()
