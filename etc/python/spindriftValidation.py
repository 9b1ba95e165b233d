"""Spindrift — what the validation cases' evaluate.py and the utilities' plotting scripts
(spindriftBenchPlot.py, spindriftStressPlot.py) share: readers of a case's dictionaries,
postProcessing .dat files, written time directories and their fluid.vtp, CSV tables, and the
plotting conventions (Agg backend, legends beside or below the data, labels that do not overlap,
figures saved with nothing cut off).

A script finds this module in $SPINDRIFT_DIR/etc/python (etc/RunFunctions exports SPINDRIFT_DIR)
or in the etc/python of the source tree it is in; the utilities' plotting scripts, installed in
share/spindrift/, also in the etc/python beside them, where the module is installed.
"""
import csv
import os
import re
import sys

import numpy as np

# Definitions of the cases' error figures (the first "Figure:" line of an evaluate.py), for plots
# that show a figure by its name: name -> (axis label with units, one-line definition).
FIGURE_DEFINITIONS = {
    "frontRMS": ("frontRMS: RMS of $Z - Z_{exp}$ over $T \\leq 3$ [-]",
                 "frontRMS: RMS of Z − Z_exp over the experimental points with T ≤ 3, against Martin & Moyce "
                 "(1952), n² = 2; Z = surge front / column width a and T = n t √(g/a) are dimensionless."),
    "bottomPressureError": ("bottomPressureError [%]",
                            "bottomPressureError: |p − ρ0 g (H − z)| / (ρ0 g (H − z)) at the bottom probe, time "
                            "average over the last quarter of the run."),
    "wallArrival": ("wallArrival: $T = t\\sqrt{g/H}$ of the front at the far wall [-]",
                    "wallArrival: T = t √(g/H) at which the surge front (a particle centre within H/4 of the floor) is "
                    "first within one particle spacing of the far wall (Colagrossi & Landrini 2003 dam break; "
                    "published δ-SPH: 2.37–2.41)."),
    "velocityL2": ("velocityL2: relative L2 velocity error [-]",
                   "velocityL2: largest relative L2 error of the particle velocities against the exact solution "
                   "over the checked times, √(Σ |u − u_exact|² / Σ |u_exact|²)."),
}


class Table:
    """Columns of numbers with named columns, the first being Time (postProcessing layout), and
    their units ("s", "Pa", "%", ...; None for a file without the units line)."""

    def __init__(self, columns, data, units=None):
        self.columns = columns
        self.data = data
        self.units = units

    def unit(self, name):
        return self.units[self.columns.index(name)] if self.units else None

    def __getitem__(self, name):
        if name not in self.columns:
            raise KeyError("no column '%s' (columns: %s)" % (name, ", ".join(self.columns)))
        return self.data[:, self.columns.index(name)]

    @property
    def time(self):
        return self.data[:, 0]


def read_table(path):
    """A whitespace-separated table whose first line is '# name name ...' (and whose second,
    in postProcessing files, '# [unit] [unit] ...'); None if the file is missing or holds no rows."""
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        lines = fh.read().splitlines()
    rows = [line for line in lines[1:] if line.strip() and not line.startswith("#")]
    if not rows:
        return None
    units = None
    if len(lines) > 1 and lines[1].startswith("# ["):
        units = [u.strip("[]") for u in lines[1].lstrip("#").split()]
    return Table(lines[0].lstrip("#").split(), np.genfromtxt(rows, ndmin=2), units)


def read_dat(name, case="."):
    """postProcessing/<name>/<start time>/<name>.dat of every start-time folder, in time order."""
    base = os.path.join(case, "postProcessing", name)
    if not os.path.isdir(base):
        sys.exit("no %s: did the run write the '%s' function object?" % (base, name))
    parts = [read_table(os.path.join(base, f, name + ".dat")) for f in sorted(os.listdir(base), key=float)]
    parts = [p for p in parts if p is not None]
    if not parts:
        sys.exit("%s holds no rows" % base)
    return Table(parts[-1].columns, np.vstack([p.data for p in parts]), parts[-1].units)


def _dictionary_text(path):
    with open(path) as fh:
        text = fh.read()
    return re.sub(r"//.*", "", re.sub(r"/\*.*?\*/", "", text, flags=re.S))


def _value(text):
    text = text.strip()
    if text.startswith("("):
        return np.array([float(v) for v in text.strip("()").split()])
    try:
        return float(text)
    except ValueError:
        return text


def surface_tension_sigma(case="."):
    """sigma [N/m] of the surfaceTension dictionary of <case>/system/sphSchemes (exits without one)."""
    text = _dictionary_text(os.path.join(case, "system", "sphSchemes"))
    block = re.search(r"\bsurfaceTension\s*\{([^}]*)\}", text)
    if not block:
        sys.exit("%s/system/sphSchemes has no surfaceTension dictionary" % case)
    return float(re.search(r"\bsigma\s+([-+0-9.eE]+)\s*;", block.group(1)).group(1))


def finish(failures):
    """A check script's last words: FAILED with the failures and exit status 1, else OK."""
    if failures:
        print("FAILED: " + "; ".join(failures))
        sys.exit(1)
    print("OK")


def fluid_properties(case="."):
    """constant/fluidProperties as a dict: numbers as floats, vectors as numpy arrays."""
    text = re.sub(r"FoamFile\s*\{[^}]*\}", "", _dictionary_text(os.path.join(case, "constant", "fluidProperties")))
    return {m.group(1): _value(m.group(2)) for m in re.finditer(r"^\s*(\w+)\s+([^;{}]+);", text, re.M)}


def geometry_box(region="fluid", case="."):
    """(min, max) of the first box of a constant/geometry section (fluid, walls), as numpy arrays."""
    text = _dictionary_text(os.path.join(case, "constant", "geometry"))
    section = text[re.search(r"\b%s\b" % region, text).end():]
    lo = re.search(r"\bmin\s*(\([^)]*\))", section).group(1)
    hi = re.search(r"\bmax\s*(\([^)]*\))", section).group(1)
    return _value(lo), _value(hi)


def periodic_extent(axis="x", case="."):
    """(lo, hi) of a periodic direction of constant/geometry."""
    text = _dictionary_text(os.path.join(case, "constant", "geometry"))
    section = text[re.search(r"\bperiodic\b", text).end():]
    lo, hi = _value(re.search(r"\b%s\s*(\([^)]*\))" % axis, section).group(1))
    return lo, hi


def written_times(case=".", file="fluid.vtp"):
    """[(time, directory name)] of the time directories holding 'file', in time order."""
    out = []
    for d in os.listdir(case):
        try:
            t = float(d)
        except ValueError:
            continue
        if os.path.exists(os.path.join(case, d, file)):
            out.append((t, d))
    return sorted(out)


def read_polydata(path):
    """A .vtp file as a vtkPolyData (VTK's XML reader: pvpython, or a python3 with vtkmodules)."""
    try:
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    except ImportError:
        sys.exit("reading %s needs VTK: run this script with pvpython (or a python3 with the vtk module)" % path)
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def read_vtp(path, array="velocity"):
    """Particle positions and one point-data array of a .vtp file, as numpy arrays."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    data = read_polydata(path)
    values = data.GetPointData().GetArray(array)
    if values is None:
        sys.exit("%s has no point array '%s'" % (path, array))
    return vtk_to_numpy(data.GetPoints().GetData()), vtk_to_numpy(values)


def read_csv(path, comment="#"):
    """Rows of a CSV file as dicts (lines starting with 'comment' skipped); [] if it is missing."""
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith(comment)))


def plot_requested(argv=None):
    """False with --no-plot on the command line or SPINDRIFT_NO_PLOT=1 in the environment."""
    argv = sys.argv if argv is None else argv
    return "--no-plot" not in argv and os.environ.get("SPINDRIFT_NO_PLOT", "0") != "1"


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def legend_beside(ax, **kwargs):
    """The axes' legend to the right of the axes, off the data."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), borderaxespad=0, fontsize=8, **kwargs)


def legend_below(fig, axes, ncol=2, **kwargs):
    """One legend for the whole figure under 'axes' (the lines labelled in any of them), off the data."""
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.canvas.draw()
    bottom = min(ax.get_tightbbox(fig.canvas.get_renderer()).transformed(fig.transFigure.inverted()).y0 for ax in axes)
    return fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, bottom - 0.01), ncol=ncol,
                      fontsize=8, frameon=False, **kwargs)


def label_points(ax, xs, ys, texts, fontsize=8):
    """Annotates each point (xs[i], ys[i]) with texts[i], each label placed at the first of a few
    offsets around its point where it overlaps neither another label nor another point."""
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    points = ax.transData.transform(np.column_stack([xs, ys]))
    placed = []
    offsets = [(4, 3), (4, -11), (-4, 3), (-4, -11), (4, 12), (-4, -20), (4, -20), (-4, 12)]
    for x, y, text in zip(xs, ys, texts):
        for dx, dy in offsets:
            label = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy),
                                ha="left" if dx > 0 else "right", fontsize=fontsize)
            box = label.get_window_extent(renderer).padded(1)
            if not any(box.contains(px, py) for px, py in points) and not any(box.overlaps(b) for b in placed):
                break
            label.remove()
        else:  # crowded all round: the first place
            label = ax.annotate(text, (x, y), textcoords="offset points", xytext=offsets[0], fontsize=fontsize)
            box = label.get_window_extent(renderer)
        placed.append(box)


def running_mean(t, y, width):
    """Centred running mean of y(t) over the samples with |t_k - t_i| <= width/2 (t increasing)."""
    c = np.concatenate([[0.0], np.cumsum(y)])
    lo = np.searchsorted(t, t - 0.5 * width, side="left")
    hi = np.searchsorted(t, t + 0.5 * width, side="right")
    return (c[hi] - c[lo]) / (hi - lo)


def first_crossing(t, y, level):
    """The first t at which y >= level (linear between the samples around it); nan if never."""
    hit = np.nonzero(y >= level)[0]
    if hit.size == 0:
        return np.nan
    k = hit[0]
    if k == 0:
        return float(t[0])
    return float(t[k - 1] + (level - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1]))


def figure_definition(name):
    """(axis label, definition) of a case's error figure; the name alone for an unknown one."""
    return FIGURE_DEFINITIONS.get(name, (name, ""))


def save(fig, path, dpi=90):
    """Saves the figure with everything drawn outside the axes (legends, captions) kept whole,
    and closes it. Returns the path."""
    fig.savefig(path, dpi=dpi, bbox_inches="tight", pad_inches=0.15)
    import matplotlib.pyplot as plt
    plt.close(fig)
    return path
