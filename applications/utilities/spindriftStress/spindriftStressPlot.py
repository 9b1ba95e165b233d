#!/usr/bin/env python3
"""spindriftStress's plots, from the tables and series it wrote into its output directory:

  stress_stillWater.png  max speed, max density error and free-surface drift over time
  stress_maxDeltaT.png   the largest stable fixed time step per combination (in units of h/c0)
  stress_jitter.png      minimum pair distance over time and the final radial distribution
  stress_impact.png      kinetic energy over its initial value and max density error over time

    spindriftStressPlot.py <output directory>
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def table(out, test):
    path = os.path.join(out, "stress_%s.csv" % test)
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(fh))


def series(out, test, combo, name):
    path = os.path.join(out, "series", test, "%s.%s.dat" % (combo, name))
    if not os.path.exists(path):
        return None, None
    with open(path) as fh:
        header = fh.readline().lstrip("#").split()
    data = np.genfromtxt(path, comments="#", ndmin=2)
    if data.size == 0:
        return None, None
    return header, data


def label(row):
    return row["combination"]


def still_water(out):
    rows = table(out, "stillWater")
    if not rows:
        return
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for j, r in enumerate(rows):
        h, s = series(out, "stillWater", r["combination"], "stats")
        if h is None:
            continue
        color = "C%d" % (j % 10)
        axes[0].semilogy(s[:, 0], s[:, h.index("maxSpeed")], color=color, lw=1, label=label(r))
        axes[1].plot(s[:, 0], 100 * s[:, h.index("rhoErrMax")], color=color, lw=1)
        lh, lv = series(out, "stillWater", r["combination"], "level")
        if lh is not None:
            cols = [i for i, c in enumerate(lh) if c.startswith("level")]
            axes[2].plot(lv[:, 0], lv[:, cols].mean(axis=1) - lv[0, cols].mean(), color=color, lw=1)
    axes[0].set_title("max speed [m/s]")
    axes[1].set_title("max density error [%]")
    axes[2].set_title("free-surface level - initial [m] (mean of 3 gauges)")
    for a in axes:
        a.set_xlabel("t [s]")
        a.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("(a) still water in a tank")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stress_stillWater.png"), dpi=80)
    plt.close(fig)


def max_delta_t(out):
    rows = table(out, "maxDeltaT")
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(max(6, 0.6 * len(rows) + 3), 5))
    names = [label(r) for r in rows]
    values = [float(r["courantOnH"]) if r["courantOnH"] else 0.0 for r in rows]
    colors = ["C2" if r["status"] == "ok" else "C1" if r["status"] == "atCap" else "C3" for r in rows]
    ax.bar(range(len(rows)), values, color=colors)
    for i, r in enumerate(rows):
        if r["status"] not in ("ok", "atCap"):
            ax.text(i, 0, r["status"], rotation=90, ha="center", va="bottom", fontsize=8)
        elif r["status"] == "atCap":
            ax.text(i, values[i], ">=", ha="center", va="bottom", fontsize=8)
    ax.set_xticks(range(len(rows)))
    ax.set_xticklabels(names, rotation=60, ha="right", fontsize=7)
    ax.set_ylabel("largest stable fixed $\\Delta t$ [h / c$_0$]")
    ax.set_title("(b) largest stable time step (still-water tank)")
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stress_maxDeltaT.png"), dpi=80)
    plt.close(fig)


def jitter(out):
    rows = table(out, "jitter")
    if not rows:
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    for j, r in enumerate(rows):
        color = "C%d" % (j % 10)
        h, s = series(out, "jitter", r["combination"], "stats")
        if h is not None:
            dx = s[0, h.index("minPairDistance")] / float(r["minPairStart_dx"]) if r["minPairStart_dx"] else 1
            a.plot(s[:, 0], s[:, h.index("minPairDistance")] / dx, color=color, lw=1, label=label(r))
        path = os.path.join(out, "series", "jitter", r["combination"] + ".rdf.dat")
        if os.path.exists(path):
            g = np.genfromtxt(path, comments="#", ndmin=2)
            b.plot(g[:, 0], g[:, 1], color=color, lw=1)
    a.set_xlabel("t [s]")
    a.set_ylabel("min pair distance / dx")
    a.set_title("clustering: closest pair")
    a.legend(fontsize=7)
    a.grid(alpha=0.3)
    b.set_xlabel("r / dx")
    b.set_ylabel("g(r)")
    b.set_title("radial distribution at the end")
    b.grid(alpha=0.3)
    fig.suptitle("(c) jittered lattice at rest (periodic, no gravity)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stress_jitter.png"), dpi=80)
    plt.close(fig)


def impact(out):
    rows = table(out, "impact")
    if not rows:
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
    for j, r in enumerate(rows):
        color = "C%d" % (j % 10)
        h, s = series(out, "impact", r["combination"], "stats")
        if h is None:
            continue
        ke = s[:, h.index("kineticEnergy")]
        a.plot(s[:, 0], ke / ke[0], color=color, lw=1, label=label(r) + ("" if r["status"] == "ok" else " (" + r["status"] + ")"))
        b.plot(s[:, 0], 100 * s[:, h.index("rhoErrMax")], color=color, lw=1)
    a.set_xlabel("t [s]")
    a.set_ylabel("kinetic energy / initial")
    a.legend(fontsize=7)
    a.grid(alpha=0.3)
    b.set_xlabel("t [s]")
    b.set_ylabel("max density error [%]")
    b.grid(alpha=0.3)
    fig.suptitle("(d) block thrown at a wall at 10 m/s")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stress_impact.png"), dpi=80)
    plt.close(fig)


def main():
    out = sys.argv[1]
    still_water(out)
    max_delta_t(out)
    jitter(out)
    impact(out)


if __name__ == "__main__":
    main()
