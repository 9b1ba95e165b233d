"""The physics of a tutorial's run, read from the times it wrote (run with pvpython).

    pvpython tutorialPhysics.py <case> [checks]

checks (each optional; a failed one prints why and the script exits 1):
  --hydrostatic-start TOL   at t = 0 every fluid particle's pressure is within TOL rho0 g H of
                            rho0 g (H - z), H the top of its fluid block (one block: the highest particle)
  --max-density-error E     at every written time after t = 0: max |rho - rho0|/rho0 <= E
  --inside                  no fluid particle centre past the walls' inner faces (constant/geometry's
                            walls; up to PAST_FACE = 0.05 dx)
  --front CSV SERIES A N BAND
                            the surge front (largest horizontal coordinate, from the column's back
                            wall) against the experiment's series (T = N t sqrt(g/A), Z = x/A) at
                            every written time inside the data's T range: |Z - Z_exp| <= BAND
  --energy FRACTION         kinetic + potential energy of the fluid never exceeds its initial
                            value by more than FRACTION of the energy it can release (initial
                            minus the still, levelled state's)
  --volume TOL              the fluid's volume, sum of m/rho, within TOL of its initial value at
                            every time, and its particle count kept (mass conserved)
  --rise DH                 the free surface's highest point rises by at least DH [m] at some time
  --outside-of WALL         no fluid particle centre inside the box of the wall system WALL's
                            particle centres (a moving wall: its own file at every time)
  --still-bottom TOL SPEED  (a tank at rest) the bottom row's mean pressure within TOL of
                            rho0 g H and the largest speed below SPEED at the last time
  --wall-slide T0 T1        (2D) fluid left on a side wall slides down it: the particles within 2 dx
                            of a side wall's face and more than dx above the free surface beside
                            it (the highest particle 4-8 dx from that face), at every written
                            time in [T0, T1], move at a median speed of at least the surface
                            speed of a film one particle thick draining down a no-slip wall,
                            g dx^2 / (2 nu) (Nusselt; nu: fluidProperties' viscosity); slower,
                            they are held by more than the case's viscosity holds a film
  --floats BODY FROM TOL    (2D) the box body BODY (constant/geometry bodies, its density) floats
                            at Archimedes' draft d = rho_b/rho0 h: its draft, the still level
                            (what the case's waterLevel gauges read from FROM on; without gauges,
                            the water's area at the start plus B d over the tank's width) less
                            the bottom of the body (the level its centre of mass decays to from
                            FROM on, a damped heave fitted, less h/2), within the fraction TOL of
                            d; upright (tilt < 2 degrees) at every time
"""
import argparse
import glob
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.environ.get("SPINDRIFT_DIR", ""), "etc", "python"))
import spindriftValidation as sv  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

failures = []
# how far a fluid particle centre may be past a wall's face (--inside), in dx
PAST_FACE = 0.05


def check(ok, message):
    print(("ok   " if ok else "FAIL ") + message)
    if not ok:
        failures.append(message)


def heave_at_rest(t, y):
    """The level a lightly damped heave decays to: y(t) = y0 + exp(-k s) (a cos w s + b sin w s),
    s = t - t[0], fitted by least squares (y0, a, b linear; w and k searched on a grid, then
    refined). A plain mean over a window that holds no whole number of periods is off by up to
    the amplitude over the number of periods it holds. Returns y0, the amplitude at t[0], w, k."""
    s = t - t[0]
    span = max(s[-1], 1e-12)
    spacing = np.min(np.diff(t)) if len(t) > 1 else span
    best = (np.inf, float(np.mean(y)), 0.0, 1.0, 0.0)

    def fit(w, k):
        e = np.exp(-k * s)
        A = np.column_stack([np.ones_like(s), e * np.cos(w * s), e * np.sin(w * s)])
        c, *_ = np.linalg.lstsq(A, y, rcond=None)
        return float(np.sum((A @ c - y) ** 2)), c

    # periods from four samples to twice the window; decay up to 8 e-foldings over the window
    omegas = np.linspace(2 * np.pi / (2 * span), 2 * np.pi / (4 * spacing), 400)
    decays = np.linspace(0, 8 / span, 41)
    for w in omegas:
        for k in decays:
            r, c = fit(w, k)
            if r < best[0]:
                best = (r, c[0], float(np.hypot(c[1], c[2])), w, k)
    dw, dk = omegas[1] - omegas[0], decays[1] - decays[0]
    for w in np.linspace(best[3] - dw, best[3] + dw, 21):
        for k in np.linspace(max(0, best[4] - dk), best[4] + dk, 21):
            r, c = fit(w, k)
            if r < best[0]:
                best = (r, c[0], float(np.hypot(c[1], c[2])), w, k)
    return float(best[1]), best[2], best[3], best[4]


def written_dat_headers(case):
    """(name, first line) of every function object's postProcessing/<name>/<time>/<name>.dat."""
    for path in glob.glob(os.path.join(case, "postProcessing", "*", "*", "*.dat")):
        name = os.path.basename(os.path.dirname(os.path.dirname(path)))
        if os.path.basename(path) == name + ".dat":
            with open(path) as f:
                yield name, f.readline()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--hydrostatic-start", type=float)
    ap.add_argument("--max-density-error", type=float)
    ap.add_argument("--inside", action="store_true")
    ap.add_argument("--front", nargs=5, metavar=("CSV", "SERIES", "A", "N", "BAND"))
    ap.add_argument("--energy", type=float)
    ap.add_argument("--volume", type=float)
    ap.add_argument("--rise", type=float)
    ap.add_argument("--outside-of")
    ap.add_argument("--still-bottom", nargs=2, type=float, metavar=("TOL", "SPEED"))
    ap.add_argument("--floats", nargs=3, metavar=("BODY", "FROM", "TOL"))
    ap.add_argument("--wall-slide", nargs=2, type=float, metavar=("T0", "T1"))
    args = ap.parse_args()
    case = args.case

    props = sv.fluid_properties(case)
    rho0 = props["rho0"]
    gvec = np.asarray(props.get("gravity", np.array([0.0, -9.81, 0.0])), dtype=float)
    g = float(np.linalg.norm(gvec))
    up = int(np.argmax(np.abs(gvec)))  # the vertical axis
    horizontal = 0
    dx = props["particleSpacing"]
    times = sv.written_times(case)
    check(len(times) >= 2, "%d times written" % len(times))
    if len(times) < 2:
        return
    states = []
    for t, d in times:
        path = os.path.join(case, d, "fluid.vtp")
        x, v = sv.read_vtp(path, "velocity")
        _, rho = sv.read_vtp(path, "density")
        _, p = sv.read_vtp(path, "pressure")
        states.append((t, x, v, rho, p))
    t0, x0, v0, rho_0, p0 = states[0]
    dims = int(props.get("dimension", 2))
    volume = dx ** dims

    if args.hydrostatic_start is not None:
        H = x0[:, up].max() + 0.5 * dx  # the block's top: half a spacing above its highest row
        expected = rho0 * g * (H - x0[:, up])
        err = np.max(np.abs(p0 - expected)) / (rho0 * g * H)
        check(err <= args.hydrostatic_start,
              "t = 0: max |p - rho0 g (H - z)| = %.2f %% of rho0 g H = %.0f Pa (bound %.1f %%)"
              % (100 * err, rho0 * g * H, 100 * args.hydrostatic_start))

    if args.max_density_error is not None:
        # compression, as the solvers' logs: a summed density falls short at a free surface by
        # design, and a deficit is not what the pressure solver controls
        worst = max((np.max(rho - rho0) / rho0, t) for t, _, _, rho, _ in states[1:])
        check(worst[0] <= args.max_density_error,
              "max compression (rho - rho0)/rho0 after t = 0: %.2f %% at t = %g (bound %.1f %%)"
              % (100 * worst[0], worst[1], 100 * args.max_density_error))

    if args.inside:
        # the walls' inner faces: no particle centre past one (issue 35; the boundary models'
        # collision keeps them out, docs/MODELS.md §collision), up to PAST_FACE dx of the step's
        # prediction against where the integrator puts the particle
        lo, hi = sv.geometry_box("walls", case)
        lo = lo[:dims] - PAST_FACE * dx
        hi = hi[:dims] + PAST_FACE * dx
        hi[up] = np.inf  # the walls' open top: a splash may rise above them
        n = len(x0)
        worst = (-np.inf, 0.0, 0)
        for t, x, _, _, _ in states:
            past = np.maximum(lo - x[:, :dims], x[:, :dims] - hi).max(axis=1)  # > 0: through a wall
            if past.max() > worst[0]:
                worst = (past.max(), t, int(np.sum(past > 0)))
        counts_kept = all(len(x) == n for _, x, _, _, _ in states)
        check(worst[2] == 0 and counts_kept,
              "no fluid particle through a wall (the deepest centre %.2f dx past a wall face at t = %g, limit %g; "
              "%d through; %d particles at every time: %s)"
              % ((worst[0] + PAST_FACE * dx) / dx, worst[1], PAST_FACE, worst[2], n, counts_kept))

    def energy(x, v):
        return float(np.sum(0.5 * np.sum(v * v, axis=1) + g * x[:, up]))  # per unit mass

    if args.energy is not None:
        lo, hi = sv.geometry_box("walls", case)
        # the still, levelled state: the same volume of particles spread over the tank's floor
        floor = np.prod([hi[k] - lo[k] for k in range(dims) if k != up])
        level = len(x0) * volume / floor
        rest = len(x0) * g * (lo[up] + 0.5 * level)
        e0 = energy(x0, v0)
        releasable = e0 - rest
        worst = max((energy(x, v) - e0, t) for t, x, v, _, _ in states[1:])
        check(releasable > 0 and worst[0] <= args.energy * releasable,
              "energy above its initial value: %.2f %% of the releasable energy at most (t = %g; bound %.1f %%)"
              % (100 * worst[0] / releasable, worst[1], 100 * args.energy))
        final = energy(states[-1][1], states[-1][2]) - rest
        print("     energy left at t = %g: %.1f %% of the releasable" % (states[-1][0], 100 * final / releasable))

    if args.front:
        csv, series, a, n, band = args.front
        a, n, band = float(a), float(n), float(band)
        rows = [r for r in sv.read_csv(os.path.join(case, csv)) if r["series"] == series]
        check(len(rows) > 2, "%d rows of series %s in %s" % (len(rows), series, csv))
        T_exp = np.array([float(r["T"]) for r in rows])
        Z_exp = np.array([float(r["Z"]) for r in rows])
        origin = x0[:, horizontal].min() - 0.5 * dx  # the column's back wall
        worst = (0.0, 0.0, 0.0, 0.0)
        compared = 0
        for t, x, _, _, _ in states[1:]:
            T = n * t * np.sqrt(g / a)
            if T < T_exp[0] or T > T_exp[-1]:
                continue
            Z = (x[:, horizontal].max() + 0.5 * dx - origin) / a
            Ze = float(np.interp(T, T_exp, Z_exp))
            compared += 1
            if abs(Z - Ze) >= abs(worst[0]):
                worst = (Z - Ze, T, Z, Ze)
        check(compared >= 3 and abs(worst[0]) <= band,
              "front against %s (%s), %d times: largest |Z - Z_exp| = %.3f at T = %.2f (Z %.2f, exp %.2f; band %.2f)"
              % (csv, series, compared, abs(worst[0]), worst[1], worst[2], worst[3], band))

    if args.volume is not None:
        v0 = np.sum(1 / rho_0)
        worst = max((abs(np.sum(1 / rho) / v0 - 1), t) for t, _, _, rho, _ in states[1:])
        kept = all(len(x) == len(x0) for _, x, _, _, _ in states)
        check(worst[0] <= args.volume and kept,
              "fluid volume sum m/rho within %.3f %% of its start (at t = %g; bound %.1f %%), %d particles at every time: %s"
              % (100 * worst[0], worst[1], 100 * args.volume, len(x0), kept))

    if args.rise is not None:
        top0 = x0[:, up].max()
        rise = max((x[:, up].max() - top0, t) for t, x, _, _, _ in states[1:])
        check(rise[0] >= args.rise, "the surface rises by %.4f m at most (t = %g; at least %g)" % (rise[0], rise[1], args.rise))

    if args.outside_of:
        worst = (0, 0.0)
        for (t, d), (_, x, _, _, _) in zip(times, states):
            path = os.path.join(case, d, args.outside_of + ".vtp")
            if not os.path.exists(path):
                path = os.path.join(case, times[0][1], args.outside_of + ".vtp")  # a fixed wall: its first file
            w = vtk_to_numpy(sv.read_polydata(path).GetPoints().GetData())
            lo, hi = w[:, :dims].min(axis=0), w[:, :dims].max(axis=0)
            inside = int(np.sum(np.all((x[:, :dims] > lo) & (x[:, :dims] < hi), axis=1)))
            if inside > worst[0]:
                worst = (inside, t)
        check(worst[0] == 0, "no fluid particle inside the wall '%s' (%d at t = %g)" % (args.outside_of, worst[0], worst[1]))

    if args.still_bottom:
        tol, speed = args.still_bottom
        t, x, v, rho, p = states[-1]
        H = x0[:, up].max() + 0.5 * dx
        bottom = x[:, up] < x[:, up].min() + 0.5 * dx
        zb = float(np.mean(x[bottom, up]))
        err = (float(np.mean(p[bottom])) - rho0 * g * (H - zb)) / (rho0 * g * H)
        vmax = float(np.max(np.linalg.norm(v, axis=1)))
        check(abs(err) <= tol and vmax <= speed,
              "t = %g: bottom row's pressure %+.2f %% of rho0 g H off rho0 g (H - z) (bound %.1f %%), "
              "max speed %.3g m/s (bound %g)" % (t, 100 * err, 100 * tol, vmax, speed))

    if args.wall_slide:
        t0, t1 = args.wall_slide
        nu = props.get("viscosity", 0.0)
        bound = g * dx * dx / (2 * nu) if nu > 0 else np.inf
        lo, hi = sv.geometry_box("walls", case)
        speeds, slowest = [], (np.inf, 0.0, 0.0)
        for t, x, v, _, _ in states:
            if t < t0 - 1e-9 or t > t1 + 1e-9:
                continue
            for distance in (x[:, horizontal] - lo[horizontal], hi[horizontal] - x[:, horizontal]):
                beside = (distance > 4 * dx) & (distance < 8 * dx)
                if not beside.any():
                    continue
                held = (distance < 2 * dx) & (x[:, up] > x[beside, up].max() + dx)
                s = np.linalg.norm(v[held], axis=1)
                speeds.extend(s)
                if len(s) and s.min() < slowest[0]:
                    slowest = (s.min(), t, float(x[held, up][np.argmin(s)]))
        median = float(np.median(speeds)) if speeds else np.inf
        check(median >= bound,
              "on the side walls above the free surface between t = %g and %g: %d particle-times, median speed "
              "%.3f m/s (at least g dx^2/(2 nu) = %.3f m/s, a film one particle thick draining; slowest %.3f m/s "
              "at t = %g, z = %.3f m)" % (t0, t1, len(speeds), median, bound, slowest[0], slowest[1], slowest[2]))

    if args.floats:
        name, start, tol = args.floats[0], float(args.floats[1]), float(args.floats[2])
        lo, hi = sv.geometry_box("bodies", case)
        text = sv._dictionary_text(os.path.join(case, "constant", "geometry"))
        density = float(re.search(r"\bdensity\s+([^;]+);", text[re.search(r"\bbodies\b", text).end():]).group(1))
        tank_lo, tank_hi = sv.geometry_box("walls", case)
        width, h = tank_hi[horizontal] - tank_lo[horizontal], hi[up] - lo[up]
        draft = density / rho0 * h
        # The still level the body floats in: what the case's waterLevel gauges read over the
        # window (the mass-based surface, away from the body), as an experimenter measures it;
        # without gauges, the water's area (its particles' volumes at the start, m/rho) and the
        # body's displacement B d over the tank's width. (A solver that sums its density packs
        # the water a little as the lattice disorders, 0.3-0.8 % at rest: the gauges see that,
        # a level from the start's volumes does not.)
        level_source = "the water's volume at the start with the body's displacement"
        level = tank_lo[up] + (np.sum(1 / rho_0) * np.mean(rho_0) * volume + (hi[horizontal] - lo[horizontal]) * draft) / width
        gauges = sorted({name for name, header in written_dat_headers(case) if "level(" in header})
        if gauges:
            table = sv.read_dat(gauges[0], case)
            inside = table.time >= start - 1e-9
            if inside.any():
                level = float(np.mean(table.data[inside, 1:]))
                level_source = "the gauges of '%s', mean over t >= %g" % (gauges[0], start)
        expected = level - draft + h / 2
        centres, tilts, heave_times = [], [], []
        for t, d in times:
            body = sv._dictionary_text(os.path.join(case, d, "uniform", "bodies"))
            entry = body[re.search(r"\b%s\b" % re.escape(name), body).end():]
            position = [float(v) for v in re.search(r"\bposition\s*\(([^)]*)\)", entry).group(1).split()]
            q = [float(v) for v in re.search(r"\borientation\s*\(([^)]*)\)", entry).group(1).split()]
            tilts.append(np.degrees(2 * np.arccos(min(1.0, abs(q[0])))))
            if t >= start:
                centres.append(position[up])
                heave_times.append(t)
        mean, amplitude, omega, decay = heave_at_rest(np.array(heave_times), np.array(centres))
        measured = level - (mean - h / 2)  # the draft: the still level less the body's bottom
        error = measured / draft - 1
        check(len(centres) >= 8 and abs(error) <= tol and max(tilts) < 2,
              "body '%s' (density %g) floats: draft %.5f m against Archimedes' %.4f m: %+.2f %% (bound %g %%); "
              "centre of mass at rest %.5f m (the heave over %d times from t = %g fitted: +-%.4f m at the window's "
              "start, period %.3f s, decay rate %.2f /s) against %.5f m (still level %.5f m: %s): %+.2f mm = %+.3f dx; "
              "largest tilt %.2f degrees"
              % (name, density, measured, draft, 100 * error, 100 * tol, mean, len(centres), start, amplitude,
                 2 * np.pi / omega, decay, expected, level, level_source, 1000 * (mean - expected), (mean - expected) / dx,
                 max(tilts)))


main()
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")
