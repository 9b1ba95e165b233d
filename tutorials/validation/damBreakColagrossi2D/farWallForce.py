#!/usr/bin/env python3
"""damBreakColagrossi2D: the force of the water on the far wall, two ways (issue 37's target).

The case is cloned with its far wall made a wall of its own (`farWall`: the tank's right side
and its corner under it, as many layers as the tank's; the tank is open on that side), and two
function objects added: `forces` on farWall (the reactions of the pair terms, every 0.5 ms) and
a line of pressure probes 1 mm inside the wall's face, every dx/2 from the floor up to 3 m. The
run's force per metre of depth, F_x, is set beside the probes' pressure integrated over the
wall's height, P = integral of p dy, from the floor up to the first probe with no fluid within
its kernel's reach (the water standing against the wall; spray above it is left out).

  farWallForce.py [--res 40] [--endT 5] [--threads 1] [--work DIR] [--spindrift BIN] [--no-plot]
                  [--evaluate-only]

Prints 'Figure:' lines (T = t sqrt(g/H), forces in units of rho0 g H^2: twice the hydrostatic
force of the initial column on a wall):
  forceDifference    the time means of F_x and P over 4 <= T <= endT (water standing against the
                     wall) against each other, %; forceMean: both means
  forceRMSDifference RMS over the same window of the difference of their 5 ms running means, %
                     of forceMean
  runUpDifference    the means' difference over 2.5 <= T <= 4 (the jet running up the wall), %
  impactPeak         the largest 5 ms running mean of each at the first impact (T <= 2.6), and T
  forcePeak          the largest of the run, and T
and writes farWallForce.csv (T, F_x, P) in the run's directory, and farWallForce.png beside it.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(HERE, "..", "..", "..")) if d]
import spindriftValidation as sv  # noqa: E402

H, L, G, RHO0 = 0.6, 3.21, 9.81, 1000.0
WINDOW_START = 2.5      # T: the surge reaches the wall at T = 2.4-2.5
COLUMN_START = 4.0      # T: from here on water stands against the wall (before it: the run-up jet)
RUNNING_MEAN = 5e-3     # s


def set_keyword(path, keyword, value):
    text = open(path).read()
    text, n = re.subn(r"^(%s\s+)[^;]*;" % re.escape(keyword), r"\g<1>%s;" % value, text, count=1, flags=re.M)
    if n != 1:
        sys.exit("%s: no '%s' to set" % (path, keyword))
    open(path, "w").write(text)


def prepare(case, res, end_t):
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for d in ("constant", "system"):
        shutil.copytree(os.path.join(HERE, d), os.path.join(case, d))
    dx = H / res
    set_keyword(os.path.join(case, "constant", "fluidProperties"), "particleSpacing", "%.10g" % dx)
    set_keyword(os.path.join(case, "system", "controlDict"), "endTime", "%.10g" % (end_t / np.sqrt(G / H)))
    geo = os.path.join(case, "constant", "geometry")
    text = open(geo).read()
    layers = int(re.search(r"^\s*layers\s+(\d+);", text, re.M).group(1))
    text, n = re.subn(r"open\s+\(yMax\);", "open    (xMax yMax);       // the far wall is a wall of its own", text)
    if n != 1:
        sys.exit("%s: the tank's 'open (yMax);' not found" % geo)
    thick = layers * dx
    far = ("    farWall     // the tank's right side, the corner under it included\n    {\n        type    box;\n"
           "        min     (%.10g %.10g 0);\n        max     (%.10g 3.6 0);\n    }\n" % (L, -thick, L + thick))
    i = text.index("walls")
    j = text.index("{", i) + 1
    text = text[:j] + "\n" + far + text[j:]
    open(geo, "w").write(text)
    ys = np.arange(0.5 * dx / 2, 3.0, dx / 2)
    probes = " ".join("(%.6g %.6g 0)" % (L - 0.001, y) for y in ys)
    functions = ("    farWallForce\n    {\n        type forces;\n        patches (farWall);\n        CofR (%g 0 0);\n"
                 "        writeControl runTime;\n        writeInterval 5e-4;\n    }\n"
                 "    farWallLine\n    {\n        type probes;\n        fields (pressure);\n        probeLocations (%s);\n"
                 "        writeControl runTime;\n        writeInterval 5e-4;\n    }\n" % (L, probes))
    ctl = os.path.join(case, "system", "controlDict")
    text = open(ctl).read()
    i = text.index("functions")
    j = text.index("{", i) + 1
    open(ctl, "w").write(text[:j] + "\n" + functions + text[j:])
    return dx


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--res", type=int, default=40)
    ap.add_argument("--endT", type=float, default=5.0)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--work", default="farWallForce")
    ap.add_argument("--spindrift", default=shutil.which("spindrift") or "spindrift")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--evaluate-only", action="store_true", help="evaluate an earlier run in --work")
    args = ap.parse_args()
    case = os.path.abspath(args.work)
    if not args.evaluate_only:
        prepare(case, args.res, args.endT)
        with open(os.path.join(case, "log.spindrift"), "w") as log:
            r = subprocess.run([args.spindrift, "-case", case, "-threads", str(args.threads)], stdout=log, stderr=subprocess.STDOUT)
        if r.returncode != 0:
            sys.exit("the run failed: %s/log.spindrift" % case)

    force = sv.read_table(os.path.join(case, "postProcessing", "farWallForce", "0", "force.dat"))
    line = sv.read_dat("farWallLine", case)
    scale = RHO0 * G * H * H   # the hydrostatic force of the initial column on a wall is half of it
    t = force.data[:, 0]
    fx = force.data[:, force.columns.index("total_x")] / scale
    ys = np.array([float(c[2:-1].split(",")[1]) for c in line.columns[1:]])
    # the water against the wall: from the floor up to the first probe with no fluid around it
    # (spray above it is left out: a lone particle reads as a full pressure through Shepard's
    # normalisation, though it pushes the wall with its own small volume only)
    raw = line.data[:, 1:]
    dry = ~np.isfinite(raw)
    first_dry = np.where(dry.any(axis=1), dry.argmax(axis=1), raw.shape[1])
    p = np.where(np.arange(raw.shape[1])[None, :] < first_dry[:, None], np.nan_to_num(raw), 0.0)
    pt = line.data[:, 0]
    integral = np.trapz(p, ys, axis=1) / scale
    # the same sample times (forces has no t = 0 row: reactions exist from the first step on)
    k = np.clip(np.searchsorted(pt, t), 0, len(pt) - 1)
    same = np.abs(pt[k] - t) <= 1e-9 * max(1.0, t[-1])
    if same.sum() < 0.9 * len(t):
        sys.exit("the force and the probes were not written at the same times")
    t, fx, integral = t[same], fx[same], integral[k[same]]
    T = t * np.sqrt(G / H)
    if T[-1] <= COLUMN_START:
        sys.exit("the run ended before T = %g" % COLUMN_START)
    fm, pm = sv.running_mean(t, fx, RUNNING_MEAN), sv.running_mean(t, integral, RUNNING_MEAN)

    def means(lo, hi):
        w = (T >= lo) & (T <= hi)
        return fx[w].mean(), integral[w].mean()

    def peak(v, lo, hi):
        w = (T >= lo) & (T <= hi)
        k = np.argmax(np.where(w, v, -np.inf))
        return v[k], T[k]

    f_col, p_col = means(COLUMN_START, T[-1])
    f_run, p_run = means(WINDOW_START, COLUMN_START)
    w = T >= COLUMN_START
    print("Figure: forceDifference = %.2f %% (F_x against the probes' integral, mean over %g <= T <= %.3g)"
          % (100 * (f_col - p_col) / p_col, COLUMN_START, T[-1]))
    print("Figure: forceMean = %.4f rho0 g H^2 (probes: %.4f)" % (f_col, p_col))
    print("Figure: forceRMSDifference = %.2f %% of forceMean (5 ms running means, %g <= T <= %.3g)"
          % (100 * np.sqrt(np.mean((fm[w] - pm[w]) ** 2)) / f_col, COLUMN_START, T[-1]))
    print("Figure: runUpDifference = %.2f %% (the same over the run-up, %g <= T <= %g: force %.4f, probes %.4f)"
          % (100 * (f_run - p_run) / p_run, WINDOW_START, COLUMN_START, f_run, p_run))
    print("Figure: impactPeak = %.4f rho0 g H^2 at T = %.3f (probes: %.4f at T = %.3f; first impact, T <= %g)"
          % (*peak(fm, 0, WINDOW_START + 0.1), *peak(pm, 0, WINDOW_START + 0.1), WINDOW_START + 0.1))
    print("Figure: forcePeak = %.4f rho0 g H^2 at T = %.3f (probes: %.4f at T = %.3f; the largest)"
          % (*peak(fm, 0, T[-1]), *peak(pm, 0, T[-1])))
    np.savetxt(os.path.join(case, "farWallForce.csv"), np.c_[T, fx, integral], delimiter=",",
               header="T,F_x/(rho0 g H^2),probes/(rho0 g H^2)", comments="")
    if not args.no_plot and sv.plot_requested([]):
        plt = sv.pyplot()
        fig, ax = plt.subplots(figsize=(8, 4))
        ax.plot(T, fm, label="forces on farWall (5 ms mean)")
        ax.plot(T, pm, "--", label="probes' pressure integrated over the wall (5 ms mean)")
        ax.set_xlabel("T = t sqrt(g/H)")
        ax.set_ylabel("F_x / (rho0 g H^2)")
        ax.set_xlim(2, T[-1])
        ax.legend()
        sv.save(fig, os.path.join(case, "farWallForce.png"))


if __name__ == "__main__":
    main()
