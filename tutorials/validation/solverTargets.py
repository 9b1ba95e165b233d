#!/usr/bin/env pvpython
"""The walls' targets of issue 35 for every pressure solver of the damBreak2D tutorial's
one-word swap (its `pressureSolvers` entries and its system/sphSolution), measured on:

  colagrossi  tutorials/validation/damBreakColagrossi2D (its own models, the `pressure { }` block
              replaced by the damBreak2D entry; wcsph keeps the case's own), H/RES, up to T = ENDT;
              evaluate.py's figures: wallPenetration, p4Mean (vs De Courcy's p4MeanRef),
              pressureOscillation, minPairDistance, maxDensityError, wallArrival, pressureNoise
  tank        tutorials/validation/hydrostaticTank2D (2 s of still water), the block swapped the
              same way: bottomPressureError (%, probe 1.5 h above the floor) and its noise
              (bottomPressureNoise, the standard deviation in %), the bottom row's mean
              pressure against rho0 g (H - z) (%) and its height over the floor (dx), the closest
              pair (dx), the largest speed at the end, the bottom corner particles' pressure
  damBreak    tutorials/damBreak2D with `pressure $pressureSolvers.X;` (the one-word swap), and
              (damBreakBox) the same with a box obstacle on the floor: penetration past any wall
              face (dx), the closest pair (dx), the largest density error, the first fluid row's
              height over the floor at the last time (dx: the mean height of the particles
              within 1.5 dx of the floor, and the fraction of them below 0.25 dx)

  pvpython solverTargets.py [--solvers wcsph,pcisph,...] [--cases colagrossi,tank,damBreak,damBreakBox]
                            [--res 40] [--endT 7] [--threads 1] [--jobs 1] [--work DIR]

Prints one table per case, and writes it as CSV to DIR/<case>-H<res>.csv (colagrossi) or
DIR/<case>.csv. The runs go to DIR (default: ./solverTargets), one clone per case and solver;
an existing finished run (its log says End) is evaluated again, not re-run.
"""
import argparse
import concurrent.futures
import csv
import glob
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "etc", "python"))
import spindriftValidation as sv  # noqa: E402

SOLVERS = ["wcsph", "pcisph", "iisph", "dfsph", "pbf", "relaxedPbf"]
SQRT_G_OVER_H = np.sqrt(9.81 / 0.6)  # Colagrossi: T = t sqrt(g/H)


def block(text, name):
    """(start, end) of the sub-dictionary `name { ... }` at the top level of a dictionary text."""
    m = re.search(r"^%s\s*\{" % re.escape(name), text, re.M)
    if not m:
        return None
    depth, i = 0, m.end() - 1
    while i < len(text):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return m.start(), i + 1
        i += 1
    raise ValueError("unbalanced braces after " + name)


def solver_entry(solver):
    """The body of damBreak2D's pressureSolvers.<solver> entry."""
    text = open(os.path.join(ROOT, "tutorials", "damBreak2D", "system", "sphSchemes")).read()
    s, e = block(text, "pressureSolvers")
    inner = text[s:e]
    m = re.search(r"\n\s*%s\s*\{" % solver, inner)
    depth, i = 0, m.end() - 1
    while True:
        if inner[i] == "{":
            depth += 1
        elif inner[i] == "}":
            depth -= 1
            if depth == 0:
                return inner[m.end():i]
        i += 1


def set_keyword(path, keyword, value):
    text = open(path).read()
    new, n = re.subn(r"^(%s\s+)[^;]*;" % re.escape(keyword), r"\g<1>%s;" % value, text, flags=re.M)
    if n == 0:
        raise ValueError("%s: no keyword %s" % (path, keyword))
    open(path, "w").write(new)


def clone(source, target):
    if os.path.exists(target):
        shutil.rmtree(target)
    os.makedirs(target)
    for name in os.listdir(source):
        if name.startswith("log.") or name.endswith(".pvd") or name.endswith(".png") or name == "postProcessing":
            continue
        if re.match(r"^[0-9.eE+-]+$", name):
            continue
        src = os.path.join(source, name)
        (shutil.copytree if os.path.isdir(src) else shutil.copy)(src, os.path.join(target, name))


SOLUTION = ""  # --solution: entries added to sphSolution's pressure block
PRESSURE = ""  # --pressure: entries added to the swapped pressure block


def swap_pressure_block(case, solver):
    """The case's `pressure { }` replaced by damBreak2D's entry, and damBreak2D's sphSolution."""
    path = os.path.join(case, "system", "sphSchemes")
    text = open(path).read()
    s, e = block(text, "pressure")
    text = text[:s] + "pressure\n{" + solver_entry(solver) + ("    " + PRESSURE + "\n" if PRESSURE else "") + "}" + text[e:]
    open(path, "w").write(text)
    path = os.path.join(case, "system", "sphSolution")
    shutil.copy(os.path.join(ROOT, "tutorials", "damBreak2D", "system", "sphSolution"), path)
    if SOLUTION:
        text = open(path).read()
        s, e = block(text, "pressure")
        open(path, "w").write(text[:e - 1] + "    " + SOLUTION + "\n}" + text[e:])


def add_options(case, name, options):
    """'options' (dictionary text) added to the top-level block 'name' of system/sphSchemes."""
    if not options:
        return
    path = os.path.join(case, "system", "sphSchemes")
    text = open(path).read()
    s, e = block(text, name)
    open(path, "w").write(text[:e - 1] + "    " + options + "\n}" + text[e:])


def add_function(case, text):
    path = os.path.join(case, "system", "controlDict")
    content = open(path).read()
    if re.search(r"^functions", content, re.M):
        s, e = block(content, "functions")
        content = content[:e - 1] + text + "\n}" + content[e:]
    else:
        content += "\nfunctions\n{\n" + text + "\n}\n"
    open(path, "w").write(content)


def run(case, spindrift, threads):
    log = os.path.join(case, "log.spindrift")
    if os.path.exists(log) and "\nEnd:" in open(log).read():
        return True
    with open(log, "w") as out:
        status = subprocess.call([spindrift, "-case", case, "-threads", str(threads)], stdout=out,
                                 stderr=subprocess.STDOUT)
    return status == 0


def figures(case, script):
    env = dict(os.environ, SPINDRIFT_DIR=ROOT, SPINDRIFT_NO_PLOT="1")
    python = os.environ.get("SPINDRIFT_PYTHON", "python3")
    if subprocess.call([python, "-c", "import numpy, matplotlib"], stderr=subprocess.DEVNULL) != 0:
        python = "/usr/bin/python3"  # as the cases' Allrun
    out = subprocess.run([python, script, "--no-plot"], cwd=case, env=env, capture_output=True, text=True)
    result = {}
    for line in out.stdout.splitlines():
        m = re.match(r"Figure: (\w+) = (\S+)", line)
        if m:
            try:
                result[m.group(1)] = float(m.group(2))
            except ValueError:
                result[m.group(1)] = m.group(2)
    if not result:
        result["error"] = (out.stdout + out.stderr).strip().splitlines()[-1:] or ["no output"]
    return result


def end_line(case):
    text = open(os.path.join(case, "log.spindrift")).read()
    m = re.search(r"End: (\d+) steps.* in ([0-9.]+) s wall time.*max density error ([0-9.eE+-]+)%"
                  r"(?:, average iterations ([0-9.]+))?", text)
    if not m:
        tail = [l for l in text.splitlines() if l.strip()][-1:]
        return {"failed": tail[0][:100] if tail else "?"}
    return {"steps": int(m.group(1)), "wall": float(m.group(2)), "maxDensityErrorLog": float(m.group(3)),
            "iterations": float(m.group(4)) if m.group(4) else 0.0}


# ---------------------------------------------------------------------------------------------
def colagrossi(solver, args):
    case = os.path.join(args.work, "colagrossi-H%d-%s" % (args.res, solver))
    if not (os.path.exists(os.path.join(case, "log.spindrift")) and
            "\nEnd:" in open(os.path.join(case, "log.spindrift")).read()):
        clone(os.path.join(HERE, "damBreakColagrossi2D"), case)
        set_keyword(os.path.join(case, "constant", "fluidProperties"), "particleSpacing", "%g" % (0.6 / args.res))
        set_keyword(os.path.join(case, "system", "controlDict"), "endTime", "%g" % (args.endT / SQRT_G_OVER_H))
        if solver != "wcsph":
            swap_pressure_block(case, solver)
        add_options(case, "boundary", args.boundary)
        if args.schemes:
            open(os.path.join(case, "system", "sphSchemes"), "a").write("\n" + args.schemes + "\n")
    ok = run(case, args.spindrift, args.threads)
    row = end_line(case)
    if ok:
        row.update(figures(case, "evaluate.py"))
    return row


def tank(solver, args):
    case = os.path.join(args.work, "tank-%s" % solver)
    done = os.path.exists(os.path.join(case, "log.spindrift")) and "\nEnd:" in open(os.path.join(case, "log.spindrift")).read()
    if not done:
        clone(os.path.join(HERE, "hydrostaticTank2D"), case)
        if solver != "wcsph":
            swap_pressure_block(case, solver)
        add_options(case, "boundary", args.boundary)
    ok = run(case, args.spindrift, args.threads)
    row = end_line(case)
    if not ok:
        return row
    row.update(figures(case, "evaluate.py"))
    props = sv.fluid_properties(case)
    rho0, g, dx = props["rho0"], abs(props["gravity"][1]), props["particleSpacing"]
    times = sv.written_times(case)
    x0, _ = sv.read_vtp(os.path.join(case, times[0][1], "fluid.vtp"), "pressure")
    H = x0[:, 1].max() + 0.5 * dx
    x, p = sv.read_vtp(os.path.join(case, times[-1][1], "fluid.vtp"), "pressure")
    _, v = sv.read_vtp(os.path.join(case, times[-1][1], "fluid.vtp"), "velocity")
    bottom = x[:, 1] < x[:, 1].min() + 0.5 * dx
    zb = float(np.mean(x[bottom, 1]))
    row["bottomRow"] = 100 * (float(np.mean(p[bottom])) - rho0 * g * (H - zb)) / (rho0 * g * H)
    row["bottomRowHeight"] = zb / dx
    lo, hi = sv.geometry_box("walls", case)
    corner = bottom & ((x[:, 0] < lo[0] + dx) | (x[:, 0] > hi[0] - dx))
    row["cornerPressure"] = float(np.max(p[corner])) / (rho0 * g * H) if corner.any() else np.nan
    row["minPair"] = min_pair(x[:, :2]) / dx
    row["maxSpeedEnd"] = float(np.max(np.linalg.norm(v, axis=1)))
    return row


def min_pair(x):
    """The closest pair's distance (all pairs, in blocks: numpy only, no scipy)."""
    best = np.inf
    for i in range(0, len(x), 512):
        d = np.linalg.norm(x[i:i + 512, None, :] - x[None, :, :], axis=2)
        d[np.arange(d.shape[0]), np.arange(i, i + d.shape[0])] = np.inf
        best = min(best, float(d.min()))
    return best


def dam_break(solver, args, obstacle):
    name = "damBreak%s-%s" % ("Box" if obstacle else "", solver)
    case = os.path.join(args.work, name)
    done = os.path.exists(os.path.join(case, "log.spindrift")) and "\nEnd:" in open(os.path.join(case, "log.spindrift")).read()
    if not done:
        clone(os.path.join(ROOT, "tutorials", "damBreak2D"), case)
        path = os.path.join(case, "system", "sphSchemes")
        text = open(path).read()
        text = re.sub(r"^pressure(\s+)\$pressureSolvers\.\w+;", r"pressure\g<1>$pressureSolvers.%s;" % solver, text, flags=re.M)
        open(path, "w").write(text)
        set_keyword(os.path.join(case, "system", "controlDict"), "endTime", "%g" % args.damBreakEnd)
        set_keyword(os.path.join(case, "system", "controlDict"), "writeInterval", "0.005")
        add_function(case, "    stats { type fieldStats; writeControl timeStep; writeInterval 1; }")
        add_options(case, "boundary", args.boundary)
        if obstacle:
            geo = os.path.join(case, "constant", "geometry")
            g = open(geo).read()
            s, e = block(g, "walls")
            g = g[:e - 1] + ("    obstacle\n    {\n        type    box;\n        min     (0.2 0 0);\n"
                              "        max     (0.24 0.04 0);\n        snapToLattice yes;\n    }\n}") + g[e:]
            open(geo, "w").write(g)
    ok = run(case, args.spindrift, args.threads)
    row = end_line(case)
    if not ok:
        return row
    props = sv.fluid_properties(case)
    dx = props["particleSpacing"]
    lo, hi = sv.geometry_box("walls", case)
    stats = sv.read_dat("stats", case)
    beyond = np.concatenate([lo[0] - stats["xMin"], stats["xMax"] - hi[0], lo[1] - stats["yMin"]])
    row["penetration"] = max(0.0, float(beyond.max())) / dx
    row["minPair"] = float(np.nanmin(stats["minPairDistance"])) / dx
    row["rhoErrMax"] = float(stats["rhoErrMax"].max())  # fieldStats: in %
    times = sv.written_times(case)
    x, _ = sv.read_vtp(os.path.join(case, times[-1][1], "fluid.vtp"), "pressure")
    near = x[:, 1] < lo[1] + 1.5 * dx
    row["firstRow"] = float(np.mean(x[near, 1] - lo[1])) / dx if near.any() else np.nan
    row["onFace"] = float(np.mean(x[near, 1] - lo[1] < 0.25 * dx)) if near.any() else np.nan
    hist, _ = np.histogram((x[x[:, 1] < lo[1] + 3 * dx, 1] - lo[1]) / dx, bins=12, range=(-0.5, 2.5))
    row["hist"] = " ".join(str(int(h)) for h in hist)
    return row


COLUMNS = {
    "colagrossi": ["wall", "iterations", "wallArrival", "wallPenetration", "p4Mean", "p4MeanRef", "p1Early",
                   "pressureNoise", "pressureOscillation", "minPairDistance", "maxDensityError", "lostParticles"],
    "tank": ["wall", "iterations", "bottomPressureError", "bottomPressureNoise", "midPressureError", "bottomRow",
             "bottomRowHeight", "cornerPressure", "minPair", "maxSpeedEnd", "maxDensityErrorLog"],
    "damBreak": ["wall", "iterations", "penetration", "minPair", "rhoErrMax", "maxDensityErrorLog", "firstRow",
                 "onFace", "hist"],
}
COLUMNS["damBreakBox"] = COLUMNS["damBreak"]


def fmt(v):
    if isinstance(v, float):
        return "%.4g" % v
    return str(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--solvers", "-solvers", default=",".join(SOLVERS))
    ap.add_argument("--cases", "-cases", default="colagrossi,tank,damBreak")
    ap.add_argument("--res", "-res", type=int, default=40)
    ap.add_argument("--endT", "-endT", type=float, default=7.0)
    ap.add_argument("--damBreakEnd", "-damBreakEnd", type=float, default=0.3)
    ap.add_argument("--boundary", "-boundary", default="", help="entries added to the boundary block, e.g. 'contactDistance 0;'")
    ap.add_argument("--schemes", "-schemes", default="", help="text appended to system/sphSchemes (colagrossi), e.g. 'shifting { type deltaPlus; }'")
    ap.add_argument("--solution", "-solution", default="", help="entries added to sphSolution's pressure block")
    ap.add_argument("--pressure", "-pressure", default="", help="entries added to the swapped pressure block")
    ap.add_argument("--threads", "-threads", type=int, default=1)
    ap.add_argument("--jobs", "-jobs", type=int, default=1)
    ap.add_argument("--work", "-work", default="solverTargets")
    ap.add_argument("--spindrift", "-spindrift", default=shutil.which("spindrift") or os.path.join(ROOT, "build", "bin", "spindrift"))
    args = ap.parse_args()
    global SOLUTION, PRESSURE
    SOLUTION, PRESSURE = args.solution, args.pressure
    args.work = os.path.abspath(args.work)
    os.makedirs(args.work, exist_ok=True)
    solvers = args.solvers.split(",")
    cases = args.cases.split(",")
    functions = {"colagrossi": colagrossi, "tank": tank, "damBreak": lambda s, a: dam_break(s, a, False),
                 "damBreakBox": lambda s, a: dam_break(s, a, True)}
    jobs = [(c, s) for c in cases for s in solvers]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        results = dict(zip(jobs, pool.map(lambda j: functions[j[0]](j[1], args), jobs)))
    for c in cases:
        cols = COLUMNS[c]
        title = "%s%s" % (c, "-H%d" % args.res if c == "colagrossi" else "")
        print("\n" + title)
        print("| solver | " + " | ".join(cols) + " |")
        print("|---" * (len(cols) + 1) + "|")
        with open(os.path.join(args.work, title + ".csv"), "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["solver"] + cols)
            for s in solvers:
                r = results[(c, s)]
                if "failed" in r:
                    print("| %s | failed: %s |" % (s, r["failed"]))
                    w.writerow([s, "failed"])
                    continue
                vals = [fmt(r.get(k, "")) for k in cols]
                print("| %s | " % s + " | ".join(vals) + " |")
                w.writerow([s] + vals)


if __name__ == "__main__":
    main()
