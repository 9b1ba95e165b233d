#!/usr/bin/env python3
"""spindriftBench's plot: wall time against the case's error figure, one numbered point per model
combination, the Pareto front (no other combination is both faster and more accurate) marked,
the numbers' combinations listed beside the plot and the figure's definition under it.

    spindriftBenchPlot.py bench.csv bench.png [title]

Rows without an error figure use the maximum density error (%) instead; rows whose run did not
finish (unstable, failed, timeout, unavailable) are listed with their status.
"""
import argparse
import os
import sys

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


def arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="spindriftBench draws it itself (bench.png beside bench.csv) unless -noPlot.")
    ap.add_argument("csv", help="the bench.csv spindriftBench wrote")
    ap.add_argument("png", help="the plot to write")
    ap.add_argument("title", nargs="?", default="", help="the plot's title (e.g. the case's name)")
    args = ap.parse_args()
    if not os.path.isfile(args.csv):
        ap.error("no file %s" % args.csv)
    return args


def main():
    args = arguments()
    import_validation_module()
    from matplotlib.ticker import ScalarFormatter

    source, target, title = args.csv, args.png, args.title
    rows = sv.read_csv(source)
    ok = [r for r in rows if r["status"] == "ok"]
    use_figure = any(r["figure"] for r in ok)
    if use_figure:
        label, definition = sv.figure_definition(ok[0]["figureName"])
    else:
        label, definition = "max density error [%]", "max density error: the largest compression (ρ − ρ0) / ρ0 of a particle over the run (the solver's End: line)."

    def error(r):
        v = r["figure"] if use_figure else r["maxDensityError_pct"]
        return float(v) if v else None

    numbered = list(enumerate(rows, 1))
    points = [(float(r["wallTime_s"]), error(r), k, r) for k, r in numbered
              if r["status"] == "ok" and r["wallTime_s"] and error(r) is not None]
    plt = sv.pyplot()
    fig, (ax, key) = plt.subplots(1, 2, figsize=(12, 6), gridspec_kw={"width_ratios": [2, 1]})
    front = sorted((p for p in points if p[3]["pareto"] == "yes"), key=lambda p: p[0])
    others = [p for p in points if p[3]["pareto"] != "yes"]
    if others:
        ax.scatter([p[0] for p in others], [p[1] for p in others], color="C0", zorder=3, label="combination")
    if front:
        ax.scatter([p[0] for p in front], [p[1] for p in front], color="C3", s=60, zorder=4, label="Pareto front")
        xs, ys = [], []
        for t, e, _, _ in front:
            if xs:
                xs.append(t)
                ys.append(ys[-1])
            xs.append(t)
            ys.append(e)
        ax.plot(xs, ys, color="C3", lw=1.5, zorder=2)
    if points:
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.margins(x=0.15, y=0.1)
        ax.legend(loc="best", fontsize=8)
    ax.set_xlabel("solver wall time [s] (log scale)")
    ax.set_ylabel(label)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title("run time against error" + (": " + title if title else ""))
    sv.label_points(ax, [p[0] for p in points], [p[1] for p in points], [str(p[2]) for p in points])

    columns = list(rows[0].keys()) if rows else []
    keys = columns[1:columns.index("status")] if rows else []  # the varied dictionary entries
    table = [["no."] + (keys or ["combination"])]
    table += [[str(k)] + ([r[c] for c in keys] or [r["combination"]]) + ([] if r["status"] == "ok" else ["(%s)" % r["status"]])
              for k, r in numbered]
    widths = [max(len(line[i]) for line in table if i < len(line)) for i in range(max(map(len, table)))]
    key.axis("off")
    key.text(0, 1, "\n".join("  ".join(v.ljust(w) for v, w in zip(line, widths)).rstrip() for line in table),
             transform=key.transAxes, va="top", ha="left", family="monospace", fontsize=8)
    fig.tight_layout()
    if definition:
        fig.text(0.01, 0, definition, fontsize=8, va="top", wrap=True)
    sv.save(fig, target)


if __name__ == "__main__":
    main()
