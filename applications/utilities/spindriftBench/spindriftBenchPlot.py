#!/usr/bin/env python3
"""spindriftBench's plot: wall time against the case's error figure, one point per model
combination, the Pareto front (no other combination is both faster and more accurate) marked.

    spindriftBenchPlot.py bench.csv bench.png [title]

Rows without an error figure use the maximum density error (%) instead; rows whose run did not
finish (unstable, failed, timeout, unavailable) are listed under the plot.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else ""
    with open(source) as fh:
        rows = list(csv.DictReader(fh))
    ok = [r for r in rows if r["status"] == "ok"]
    use_figure = any(r["figure"] for r in ok)
    label = (ok[0]["figureName"] if use_figure and ok else "max density error [%]") or "error"

    def error(r):
        v = r["figure"] if use_figure else r["maxDensityError_pct"]
        return float(v) if v else None

    points = [(float(r["wallTime_s"]), error(r), r) for r in ok if r["wallTime_s"] and error(r) is not None]
    fig, ax = plt.subplots(figsize=(9, 6))
    front = sorted((p for p in points if p[2]["pareto"] == "yes"), key=lambda p: p[0])
    others = [p for p in points if p[2]["pareto"] != "yes"]
    if others:
        ax.scatter([p[0] for p in others], [p[1] for p in others], color="C0", zorder=3, label="combination")
    if front:
        ax.scatter([p[0] for p in front], [p[1] for p in front], color="C3", s=60, zorder=4, label="Pareto front")
        xs, ys = [], []
        for t, e, _ in front:
            if xs:
                xs.append(t)
                ys.append(ys[-1])
            xs.append(t)
            ys.append(e)
        ax.plot(xs, ys, color="C3", lw=1.5, zorder=2)
    for t, e, r in points:
        ax.annotate(r["combination"], (t, e), textcoords="offset points", xytext=(4, 3), fontsize=7)
    if points:
        ax.set_xscale("log")
        ax.margins(x=0.25)
    ax.set_xlabel("solver wall time [s]")
    ax.set_ylabel(label)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title("run time against error" + (": " + title if title else ""))
    failed = [r for r in rows if r["status"] != "ok"]
    if failed:
        text = "not finished: " + "; ".join("%s (%s)" % (r["combination"], r["status"]) for r in failed)
        fig.text(0.01, 0.01, text, fontsize=7, wrap=True)
        fig.subplots_adjust(bottom=0.18)
    if points:
        ax.legend(loc="best", fontsize=8)
    fig.savefig(target, dpi=90)


if __name__ == "__main__":
    main()
