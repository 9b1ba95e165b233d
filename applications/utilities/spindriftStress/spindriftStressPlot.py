#!/usr/bin/env python3
"""spindriftStress's plots, from the tables and series it wrote into its output directory:

  stress_stillWater.png  max speed, max density error and free-surface drift over time
  stress_maxDeltaT.png   the largest stable fixed time step per combination (in units of h/c0)
  stress_jitter.png      minimum pair distance over time and the final radial distribution
  stress_impact.png      kinetic energy over its initial value and max density error over time

One colour per combination, named in a legend under the panels.

    spindriftStressPlot.py <output directory>
"""
import argparse
import os
import sys
import textwrap

# etc/python/spindriftValidation.py: from $SPINDRIFT_DIR, the source tree or the installed share/spindrift
here = os.path.dirname(os.path.abspath(__file__))
sys.path[1:1] = [os.path.join(d, "etc", "python") for d in (os.environ.get("SPINDRIFT_DIR"), os.path.join(here, "..", "..", ".."), here) if d]
sv = None


def import_validation_module():
    """spindriftValidation (numpy, matplotlib), once the command line is known good."""
    global sv
    try:
        import spindriftValidation as module
    except ImportError as e:
        if e.name == "spindriftValidation":
            sys.exit("%s: %s: set SPINDRIFT_DIR to Spindrift's directory (source its etc/bashrc)" % (sys.argv[0], e))
        sys.exit("%s: %s: run it with a python3 that has numpy and matplotlib (Debian: python3-matplotlib)"
                 % (sys.argv[0], e))
    sv = module

STATUS_COLOURS = {"ok": "C2", "atCap": "C1"}  # maxDeltaT bars; any other status has no bar


def table(out, test):
    return sv.read_csv(os.path.join(out, "stress_%s.csv" % test))


def series(out, test, combo, name):
    return sv.read_table(os.path.join(out, "series", test, "%s.%s.dat" % (combo, name)))


def time_series_figure(out, test, title, panels, draw):
    """One figure of 'panels' [(x label, y label, title)] side by side; draw(axes, row, colour,
    label) plots one combination's series; one legend for all panels under them."""
    rows = table(out, test)
    if not rows:
        return
    plt = sv.pyplot()
    fig, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4.2))
    for j, r in enumerate(rows):
        label = r["combination"] + ("" if r["status"] == "ok" else " (%s)" % r["status"])
        draw(axes, r, "C%d" % (j % 10), label)
        if label not in axes[0].get_legend_handles_labels()[1]:  # a run that wrote no series
            axes[0].plot([], [], ls="none", label=label + ": no series")
    for ax, (xlabel, ylabel, panel_title) in zip(axes, panels):
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(panel_title, fontsize=10)
        ax.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    sv.legend_below(fig, axes, ncol=2 if len(panels) < 3 else 3)
    sv.save(fig, os.path.join(out, "stress_%s.png" % test), dpi=80)


def still_water(out):
    def draw(axes, r, colour, label):
        s = series(out, "stillWater", r["combination"], "stats")
        if s is None:
            return
        axes[0].semilogy(s.time, s["maxSpeed"], color=colour, lw=1, label=label)
        axes[1].plot(s.time, s["rhoErrMax"], color=colour, lw=1)
        level = series(out, "stillWater", r["combination"], "level")
        if level is not None:
            gauges = [i for i, c in enumerate(level.columns) if c.startswith("level")]
            mean = level.data[:, gauges].mean(axis=1)
            axes[2].plot(level.time, 1000 * (mean - mean[0]), color=colour, lw=1)

    time_series_figure(out, "stillWater", "(a) still water in a tank",
                       [("t [s]", "max particle speed [m/s]", "max speed"),
                        ("t [s]", "max density error [%]", "max over the particles of $(\\rho - \\rho_0) / \\rho_0$"),
                        ("t [s]", "level − initial level [mm]", "free-surface drift (mean of 3 gauges)")], draw)


def max_delta_t(out):
    rows = table(out, "maxDeltaT")
    if not rows:
        return
    plt = sv.pyplot()
    from matplotlib.patches import Patch
    names = ["\n".join(textwrap.wrap(r["combination"].replace("_", " "), 36, break_on_hyphens=False)) for r in rows]
    values = [float(r["courantOnH"]) if r["courantOnH"] else 0.0 for r in rows]
    # tall enough for the y label (a quick run has one or two bars)
    fig, ax = plt.subplots(figsize=(9, max(3.2, 1.0 + 0.45 * sum(n.count("\n") + 1 for n in names))))
    y = range(len(rows))
    ax.barh(y, values, color=[STATUS_COLOURS.get(r["status"], "C3") for r in rows])
    for i, r in enumerate(rows):
        if r["status"] not in STATUS_COLOURS:
            ax.text(0, i, " " + r["status"], va="center", ha="left", fontsize=8, color="C3")
        elif r["status"] == "atCap":
            ax.text(values[i], i, " ≥", va="center", ha="left", fontsize=9)
    ax.set_yticks(list(y))
    ax.set_yticklabels(names, fontsize=8)
    ax.invert_yaxis()
    ax.margins(x=0.08)
    ax.set_xlabel("largest stable fixed Δt [h / c$_0$] (h = kernel support radius, c$_0$ = sound speed)")
    ax.set_ylabel("model combination\n(the models it changes)")
    ax.set_title("(b) largest stable time step (still-water tank)")
    ax.grid(axis="x", alpha=0.3)
    meaning = {"ok": "stable up to this step", "atCap": "stable at every step tried (≥)"}
    sv.legend_beside(ax, handles=[Patch(color=STATUS_COLOURS[k], label=meaning[k]) for k in meaning
                                  if any(r["status"] == k for r in rows)])
    fig.tight_layout()
    sv.save(fig, os.path.join(out, "stress_maxDeltaT.png"), dpi=80)


def jitter(out):
    def draw(axes, r, colour, label):
        s = series(out, "jitter", r["combination"], "stats")
        if s is not None:
            pair = s["minPairDistance"]
            dx = pair[0] / float(r["minPairStart_dx"]) if r["minPairStart_dx"] else 1
            axes[0].plot(s.time, pair / dx, color=colour, lw=1, label=label)
        rdf = sv.read_table(os.path.join(out, "series", "jitter", r["combination"] + ".rdf.dat"))
        if rdf is not None:
            axes[1].plot(rdf.data[:, 0], rdf.data[:, 1], color=colour, lw=1)

    time_series_figure(out, "jitter", "(c) jittered lattice at rest (periodic, no gravity)",
                       [("t [s]", "closest pair distance / Δx [-]", "clustering: closest pair"),
                        ("r / Δx [-]", "radial distribution g(r) [-]", "radial distribution at the end")], draw)


def impact(out):
    def draw(axes, r, colour, label):
        s = series(out, "impact", r["combination"], "stats")
        if s is None:
            return
        ke = s["kineticEnergy"]
        axes[0].plot(s.time, ke / ke[0], color=colour, lw=1, label=label)
        axes[1].plot(s.time, s["rhoErrMax"], color=colour, lw=1)

    time_series_figure(out, "impact", "(d) block thrown at a wall at 10 m/s",
                       [("t [s]", "kinetic energy / initial [-]", "kinetic energy"),
                        ("t [s]", "max density error [%]", "max over the particles of $(\\rho - \\rho_0) / \\rho_0$")],
                       draw)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="spindriftStress draws them itself into its -output directory unless -noPlot.")
    ap.add_argument("output", help="spindriftStress's output directory (stress_<test>.csv, series/)")
    out = ap.parse_args().output
    if not os.path.isdir(out):
        ap.error("no directory %s" % out)
    import_validation_module()
    still_water(out)
    max_delta_t(out)
    jitter(out)
    impact(out)


if __name__ == "__main__":
    main()
