"""Screenshots of a Spindrift case, without a display: the fluid particles coloured by a field
(|velocity|, pressure, ...) at chosen times, the walls in grey, one PNG per field and time.

Run it with ParaView's pvbatch (its python):

    spindriftRender -case run/damBreak2D -times 0.1,0.2                          # the wrapper picks:
    xvfb-run -a -s -noreset pvbatch spindriftRender.py -- -case run/damBreak2D   # Debian's ParaView (X only)
    pvbatch --force-offscreen-rendering spindriftRender.py -- -case ...            # ParaView built with EGL/OSMesa

(the "--" keeps pvbatch from reading the script's options as its own)

Options:
    -case DIR         the case (default .): reads <case>/<case name>.pvd, the time directories it lists
    -times LIST       written times, comma-separated (as named: 0.1,0.25), or all, or latest (default)
    -fields LIST      fluid fields to colour by (default velocity,pressure); a vector field by its magnitude
    -output DIR       where the PNGs go (default <case>/screenshots): <case name>_<field>_<time>.png
    -size WxH         pixels (default 1000x500)
    -range FIELD=LO:HI  the colour range of a field (default: over the chosen times; repeatable)

The colour range of each field is common to all the chosen times, so the pictures compare; the
particles are drawn as squares of about one particle spacing (constant/fluidProperties).
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

USAGE = __doc__


def fail(message):
    sys.stderr.write("spindriftRender: %s\n" % message)
    sys.exit(1)


def parse_arguments(argv):
    args = {"case": ".", "times": "latest", "fields": "velocity,pressure", "output": None, "size": "1000x500",
            "range": {}}
    argv = [a for a in argv if a != "--"]  # pvbatch script.py -- -case ...: the options past pvbatch's own
    k = 0
    while k < len(argv):
        a = argv[k].lstrip("-")
        if a in ("h", "help"):
            print(USAGE)
            sys.exit(0)
        if a not in ("case", "times", "fields", "output", "size", "range"):
            fail("unknown option '%s'\n%s" % (argv[k], USAGE))
        if k + 1 >= len(argv):
            fail("option '%s' needs a value" % argv[k])
        value = argv[k + 1]
        if a == "range":
            m = re.match(r"^(\w+)=([-+0-9.eE]+):([-+0-9.eE]+)$", value)
            if not m:
                fail("-range %s: expected FIELD=LO:HI, e.g. pressure=0:2000" % value)
            args["range"][m.group(1)] = (float(m.group(2)), float(m.group(3)))
        else:
            args[a] = value
        k += 2
    m = re.match(r"^(\d+)x(\d+)$", args["size"])
    if not m:
        fail("-size %s: expected WxH, e.g. 1000x500" % args["size"])
    args["size"] = [int(m.group(1)), int(m.group(2))]
    args["fields"] = [f for f in args["fields"].split(",") if f]
    return args


def collection(case):
    """{time name: [(block name, file)]} from <case>/<case name>.pvd, in time order."""
    name = os.path.basename(os.path.abspath(case))
    pvd = os.path.join(case, name + ".pvd")
    if not os.path.isfile(pvd):
        fail("no %s: run the case first (spindrift -case %s)" % (pvd, case))
    times = {}
    for d in ET.parse(pvd).getroot().iter("DataSet"):
        times.setdefault(d.get("timestep"), []).append((d.get("name"), os.path.join(case, d.get("file"))))
    return name, dict(sorted(times.items(), key=lambda t: float(t[0])))


def particle_spacing(case):
    text = open(os.path.join(case, "constant", "fluidProperties")).read()
    m = re.search(r"^\s*particleSpacing\s+([-+0-9.eE]+)\s*;", re.sub(r"//.*", "", text), re.M)
    return float(m.group(1)) if m else None


def choose_times(available, request):
    names = list(available)
    if request == "all":
        return names
    if request == "latest":
        return names[-1:]
    chosen = []
    for item in request.split(","):
        match = [n for n in names if n == item or abs(float(n) - float(item)) <= 1e-9 * max(1.0, abs(float(item)))]
        if not match:
            fail("-times: no written time %s (the case has %s)" % (item, " ".join(names)))
        chosen += match
    return chosen


def main():
    args = parse_arguments(sys.argv[1:])
    try:
        from paraview import simple as pv
    except ImportError:
        fail("run me with ParaView's pvbatch (package python3-paraview), not python")
    case = args["case"]
    name, available = collection(case)
    times = choose_times(available, args["times"])
    output = args["output"] or os.path.join(case, "screenshots")
    os.makedirs(output, exist_ok=True)
    dx = particle_spacing(case)

    # readers for every block of the chosen times (a fixed wall's file is shared by the times)
    readers = {}
    for t in times:
        for block, path in available[t]:
            if path not in readers:
                readers[path] = pv.XMLPolyDataReader(FileName=[path])
                readers[path].UpdatePipeline()

    def fluid(t):
        return next(readers[p] for b, p in available[t] if b == "fluid")

    # bounds over the chosen times, for the camera and the particle size
    lo, hi = [1e300] * 3, [-1e300] * 3
    for t in times:
        for _, path in available[t]:
            b = readers[path].GetDataInformation().GetBounds()
            for a in range(3):
                lo[a], hi[a] = min(lo[a], b[2 * a]), max(hi[a], b[2 * a + 1])
    three_d = hi[2] - lo[2] > 1e-12

    # colour ranges common to the chosen times
    ranges = {}
    for field in args["fields"]:
        if field in args["range"]:
            ranges[field] = args["range"][field]
            continue
        low, high = 1e300, -1e300
        for t in times:
            array = fluid(t).PointData[field] if field in fluid(t).PointData.keys() else None
            if array is None:
                fail("the fluid of time %s has no field '%s' (fields: %s)"
                     % (t, field, " ".join(fluid(t).PointData.keys())))
            r = array.GetRange(-1 if array.GetNumberOfComponents() > 1 else 0)
            low, high = min(low, r[0]), max(high, r[1])
        if array.GetNumberOfComponents() > 1:
            low = 0.0
        ranges[field] = (low, high if high > low else low + 1)
    units = {"velocity": "m/s", "pressure": "Pa", "density": "kg/m^3", "acceleration": "m/s^2"}

    view = pv.CreateView("RenderView")
    view.ViewSize = args["size"]
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 0
    # the frame: the domain in the left 82 % of the picture (the colour bar to its right), below
    # the title; in 2D a parallel projection whose scale makes it fit
    width, height = args["size"]
    extent = [max(hi[a] - lo[a], 1e-12) for a in range(3)]
    centre = [(lo[a] + hi[a]) / 2 for a in range(3)]
    if three_d:
        pixels_per_metre = 0.6 * min(width, height) / max(extent)
    else:
        scale = max(extent[1] / 2 / 0.86, extent[0] / 2 / 0.80 * height / width)  # half the visible height
        pixels_per_metre = height / (2 * scale)
        visible_width = 2 * scale * width / height
        camera_centre = [centre[0] + (0.5 - 0.42) * visible_width, centre[1] + 0.04 * 2 * scale, centre[2]]
    # squares of about one spacing (a little more, so that the lattice shows no gaps)
    point_size = max(1.5, 1.3 * (dx or 0.01 * max(extent)) * pixels_per_metre)

    written = []
    for field in args["fields"]:
        for t in times:
            for r in readers.values():
                pv.Hide(r, view)
            for f in args["fields"]:  # the colour bar of this field only
                pv.GetScalarBar(pv.GetColorTransferFunction(f), view).Visibility = 0
            for block, path in available[t]:
                display = pv.Show(readers[path], view)
                display.SetRepresentationType("Points")
                display.PointSize = point_size
                display.RenderPointsAsSpheres = 0  # flat squares of about one spacing: the fluid reads as a body
                display.Specular = 0
                if block == "fluid":
                    vector = readers[path].PointData[field].GetNumberOfComponents() > 1
                    pv.ColorBy(display, ("POINTS", field, "Magnitude") if vector else ("POINTS", field))
                    lut = pv.GetColorTransferFunction(field)
                    lut.ApplyPreset("Turbo" if field != "pressure" else "Cool to Warm", True)
                    lut.RescaleTransferFunction(*ranges[field])
                    try:
                        lut.AutomaticRescaleRangeMode = "Never"
                    except AttributeError:
                        pass
                    display.SetScalarBarVisibility(view, True)
                    bar = pv.GetScalarBar(lut, view)
                    bar.Title = ("speed" if field == "velocity" else "%s magnitude" % field if vector else field) + (" [%s]" % units[field] if field in units else "")
                    bar.ComponentTitle = ""
                    bar.TitleColor = bar.LabelColor = [0, 0, 0]
                    bar.WindowLocation = "Any Location"
                    bar.Position = [0.85, 0.06]
                    bar.ScalarBarLength = 0.72
                    bar.HorizontalTitle = 1
                    bar.RangeLabelFormat = bar.LabelFormat = "%.3g"
                    bar.TitleFontSize = bar.LabelFontSize = 14
                    bar.Visibility = 1
                else:
                    display.ColorArrayName = ["POINTS", ""]
                    display.AmbientColor = display.DiffuseColor = [0.55, 0.55, 0.55]
            label = pv.Text(Text="%s   t = %s s   %s" % (name, t, field))
            text = pv.Show(label, view)
            text.Color = [0, 0, 0]
            text.FontSize = 14
            text.WindowLocation = "Upper Left Corner"
            if three_d:
                view.CameraPosition = [centre[0] + 1.6 * extent[0], centre[1] + 1.2 * extent[1],
                                       centre[2] + 2.2 * max(extent)]
                view.CameraFocalPoint = centre
                view.CameraViewUp = [0, 1, 0]
                view.ResetCamera(False)
            else:
                view.InteractionMode = "2D"
                view.CameraParallelProjection = 1
                view.CameraPosition = [camera_centre[0], camera_centre[1], centre[2] + 10 * max(extent)]
                view.CameraFocalPoint = camera_centre
                view.CameraViewUp = [0, 1, 0]
                view.CameraParallelScale = scale
            target = os.path.join(output, "%s_%s_%s.png" % (name, field, t))
            pv.SaveScreenshot(target, view, ImageResolution=args["size"], TransparentBackground=0)
            pv.Hide(label, view)
            pv.Delete(label)
            written.append(target)
    for w in written:
        print("Wrote " + w)


if __name__ == "__main__":
    main()
