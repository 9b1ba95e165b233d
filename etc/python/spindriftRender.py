"""Screenshots of a Spindrift case, without a display: the fluid particles coloured by a field
(|velocity|, pressure, ...) at chosen times, the walls in grey, the diffuse particles (spray,
foam, air bubbles) coloured by their type and the free-surface mesh when the case writes them,
one PNG per field and time.

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
    -diffuse yes|no   draw the diffuse particles (default yes, when the case has them): each block
                      with the point fields `type` and `lifetime` (a diffuseParticles passive
                      system's <name>.vtp), in one colour a type: spray (type 0) magenta, foam
                      (1) white, air bubbles (2) black, drawn over the fluid and the walls (the
                      bubbles are in the water); their numbers in the title
    -surface yes|no   draw the free-surface mesh (default yes, when the case has it): each block of
                      triangles without particle fields (a freeSurface function object's
                      <name>.vtp), light blue, semi-transparent
    -surfaceOpacity X the surface mesh's opacity, 0 to 1 (default 0.35)
    -fluidOpacity X   the fluid particles' opacity, 0 to 1 (default 1; 0: the surface mesh and
                      the diffuse particles alone)
    -view AZ,EL       3D only: the camera's azimuth and elevation in degrees (default -30,25): 0,0
                      looks at the domain's side along its shorter horizontal axis, up being
                      against gravity (constant/fluidProperties; y without gravity); AZ < 0 from the
                      left, EL > 0 from above

The colour range of each field is common to all the chosen times, so the pictures compare; the
particles are drawn as squares of about one particle spacing (constant/fluidProperties). In 3D
the projection is parallel (an oblique view of the whole domain, the same for all the times), and
the wall layers that face the camera (a tank's front wall, its lid, its near end) are left out,
so that the fluid shows.
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
            "range": {}, "diffuse": "yes", "surface": "yes", "surfaceOpacity": "0.35", "fluidOpacity": "1",
            "view": "-30,25"}
    argv = [a for a in argv if a != "--"]  # pvbatch script.py -- -case ...: the options past pvbatch's own
    k = 0
    while k < len(argv):
        a = argv[k].lstrip("-")
        if a in ("h", "help"):
            print(USAGE)
            sys.exit(0)
        if a not in ("case", "times", "fields", "output", "size", "range", "diffuse", "surface", "surfaceOpacity",
                     "fluidOpacity", "view"):
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
    for a in ("diffuse", "surface"):
        if args[a].lower() not in ("yes", "no", "on", "off", "true", "false"):
            fail("-%s %s: expected yes or no" % (a, args[a]))
        args[a] = args[a].lower() in ("yes", "on", "true")
    for a in ("surfaceOpacity", "fluidOpacity"):
        try:
            args[a] = float(args[a])
        except ValueError:
            args[a] = -1
        if not 0 <= args[a] <= 1:
            fail("-%s: expected a number from 0 to 1" % a)
    m = re.match(r"^([-+0-9.eE]+),([-+0-9.eE]+)$", args["view"])
    if not m or abs(float(m.group(2))) > 90:
        fail("-view %s: expected AZIMUTH,ELEVATION in degrees, e.g. -30,25" % args["view"])
    args["view"] = (float(m.group(1)), float(m.group(2)))
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


def fluid_properties(case):
    """particleSpacing and gravity from constant/fluidProperties (None where not given)."""
    text = re.sub(r"//.*", "", open(os.path.join(case, "constant", "fluidProperties")).read())
    m = re.search(r"^\s*particleSpacing\s+([-+0-9.eE]+)\s*;", text, re.M)
    g = re.search(r"^\s*gravity\s+\(\s*([-+0-9.eE]+)\s+([-+0-9.eE]+)(?:\s+([-+0-9.eE]+))?\s*\)\s*;", text, re.M)
    gravity = [float(v) for v in g.groups() if v is not None] + [0.0] if g else None
    return (float(m.group(1)) if m else None), (gravity[:3] if gravity else None)


def block_kind(path):
    """'diffuse' (point fields type and lifetime: diffuseParticles), 'surface' (a mesh without
    particle ids: freeSurface's triangles) or 'particles', read from the .vtp's XML header."""
    with open(path, "rb") as f:
        head = f.read(65536).decode("latin-1")
    head = head.split("<AppendedData")[0]
    point_data = re.search(r"<PointData[^>]*>(.*?)</PointData>", head, re.S)
    names = set(re.findall(r'Name="([^"]+)"', point_data.group(1))) if point_data else set()
    if "type" in names and "lifetime" in names:
        return "diffuse"
    if "id" not in names:
        return "surface"
    return "particles"


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


DIFFUSE_TYPES = [("spray", [0.9, 0.1, 0.8]), ("foam", [1.0, 1.0, 1.0]), ("bubbles", [0.0, 0.0, 0.0])]


def numpy_points(pv, source):
    """The points of a reader's output as a numpy array (None without points), and the output."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    data = pv.servermanager.Fetch(source)
    if data.GetNumberOfPoints() == 0:
        return None, data
    return vtk_to_numpy(data.GetPoints().GetData()), data


def facing_wall_cuts(points, spacing, toward):
    """[(axis, value, keep above)]: the planes that cut off the wall layers facing the camera.
    Along each axis the camera looks along, the planes of wall particles at the domain's near
    edge (binned a spacing thick) are a wall facing it while each holds at least half as many
    particles as the fullest plane (a tank's end, front or lid: the layers of a tank's sides,
    only their rims, hold far fewer); they are left out."""
    import numpy as np
    cuts = []
    for a in range(3):
        if abs(toward[a]) < 0.1:
            continue
        x = points[:, a]
        lo, hi = x.min(), x.max()
        if hi - lo < 2 * spacing:
            continue
        bins = np.floor((x - lo) / spacing + 0.5).astype(int)
        counts = np.bincount(bins)
        if toward[a] > 0:  # the camera on the high side: from the high edge down
            counts = counts[::-1]
        n = 0
        while n < len(counts) and counts[n] >= 0.5 * counts.max():
            n += 1
        if n == 0 or n > len(counts) / 2:
            continue
        if toward[a] > 0:
            cuts.append((a, lo + (len(counts) - n - 0.5) * spacing, False))
        else:
            cuts.append((a, lo + (n - 0.5) * spacing, True))
    return cuts


def main():
    args = parse_arguments(sys.argv[1:])
    try:
        from paraview import simple as pv
    except ImportError:
        fail("run me with ParaView's pvbatch (package python3-paraview), not python")
    import math
    import numpy as np
    case = args["case"]
    name, available = collection(case)
    times = choose_times(available, args["times"])
    output = args["output"] or os.path.join(case, "screenshots")
    os.makedirs(output, exist_ok=True)
    dx, gravity = fluid_properties(case)

    # readers for every block of the chosen times (a fixed wall's file is shared by the times),
    # and what each block holds: fluid, walls, diffuse particles, a surface mesh
    readers, kinds = {}, {}
    for t in times:
        for block, path in available[t]:
            if path not in readers:
                readers[path] = pv.XMLPolyDataReader(FileName=[path])
                readers[path].UpdatePipeline()
                kinds[path] = "fluid" if block == "fluid" else {"particles": "walls"}.get(block_kind(path),
                                                                                       block_kind(path))
    skip = {"diffuse": not args["diffuse"], "surface": not args["surface"]}

    def drawn(t):
        return [(b, p) for b, p in available[t] if not skip.get(kinds[p], False)]

    def fluid(t):
        return next(readers[p] for b, p in available[t] if b == "fluid")

    # bounds over the chosen times, for the camera and the particle size (the diffuse particles
    # excluded: a spray particle may fly out of a tank without a lid)
    lo, hi = [1e300] * 3, [-1e300] * 3
    for t in times:
        for _, path in drawn(t):
            if kinds[path] == "diffuse" or readers[path].GetDataInformation().GetNumberOfPoints() == 0:
                continue
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

    # the diffuse particles of each type at each time, for the title
    diffuse_counts = {}
    for t in times:
        for _, path in drawn(t):
            if kinds[path] == "diffuse":
                _, data = numpy_points(pv, readers[path])
                counts = [0, 0, 0]
                if data.GetNumberOfPoints():
                    from vtkmodules.util.numpy_support import vtk_to_numpy
                    kind = np.rint(vtk_to_numpy(data.GetPointData().GetArray("type"))).astype(int)
                    counts = [int(np.sum(kind == k)) for k in range(3)]
                diffuse_counts[t] = [c + d for c, d in zip(diffuse_counts.get(t, [0, 0, 0]), counts)]

    view = pv.CreateView("RenderView")
    view.ViewSize = args["size"]
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 0
    # the frame: the domain in the left 82 % of the picture (the colour bar to its right), below
    # the title, in a parallel projection whose scale makes it fit: in 2D the x-y plane; in 3D an
    # oblique view (-view AZ,EL about the up axis, against gravity)
    width, height = args["size"]
    extent = [max(hi[a] - lo[a], 1e-12) for a in range(3)]
    centre = [(lo[a] + hi[a]) / 2 for a in range(3)]
    toward = [0.0, 0.0, 1.0]  # from the domain to the camera
    if three_d:
        up = np.array(gravity if gravity and any(gravity) else [0.0, 1.0, 0.0])
        up = -up / np.linalg.norm(up) if gravity and any(gravity) else up
        horizontal = [a for a in range(3) if a != int(np.argmax(abs(up)))]
        along = np.zeros(3)
        along[max(horizontal, key=lambda a: extent[a])] = 1.0  # the picture's horizontal at AZ = 0
        along -= up * np.dot(along, up)
        along /= np.linalg.norm(along)
        toward = np.cross(along, up)  # from the domain to the camera at AZ = EL = 0
        azimuth, elevation = (math.radians(v) for v in args["view"])
        toward = (math.cos(elevation) * (math.cos(azimuth) * toward + math.sin(azimuth) * along)
                  + math.sin(elevation) * up)
        right = np.cross(-toward, up)
        right /= np.linalg.norm(right)
        screen_up = np.cross(right, -toward)
        corners = np.array([[(lo, hi)[(k >> a) & 1][a] for a in range(3)] for k in range(8)]) - np.array(centre)
        across = [np.ptp(corners @ right), np.ptp(corners @ screen_up)]
    else:
        across = extent[:2]
    scale = max(across[1] / 2 / 0.86, across[0] / 2 / 0.80 * height / width)  # half the visible height
    pixels_per_metre = height / (2 * scale)
    visible_width = 2 * scale * width / height
    shift = [(0.5 - 0.42) * visible_width, 0.04 * 2 * scale]  # right, up
    if three_d:
        camera_centre = np.array(centre) + shift[0] * right + shift[1] * screen_up
    else:
        camera_centre = [centre[0] + shift[0], centre[1] + shift[1], centre[2]]
    # squares of about one spacing (a little more, so that the lattice shows no gaps)
    spacing = dx or 0.01 * max(extent)
    point_size = max(1.5, 1.3 * spacing * pixels_per_metre)

    # in 3D the wall layers facing the camera are left out (clipped), so that the fluid shows
    sources = {p: r for p, r in readers.items()}
    if three_d:
        wall_points = [numpy_points(pv, readers[p])[0] for p in readers if kinds[p] == "walls"]
        wall_points = [w for w in wall_points if w is not None]
        if wall_points:
            cuts = facing_wall_cuts(np.concatenate(wall_points), spacing, toward)
            for p in readers:
                if kinds[p] != "walls":
                    continue
                for axis, value, keep_above in cuts:
                    normal = [0.0, 0.0, 0.0]
                    normal[axis] = 1.0 if keep_above else -1.0
                    origin = list(centre)
                    origin[axis] = value
                    clip = pv.Clip(Input=sources[p], ClipType="Plane")
                    clip.ClipType.Origin = origin
                    clip.ClipType.Normal = normal
                    clip.Invert = 0  # keeps the side the normal points to
                    try:
                        clip.Crinkleclip = 1  # whole vertices, no cut cells
                    except AttributeError:
                        pass
                    sources[p] = clip

    # the diffuse particles drawn over the fluid and the walls: moved towards the camera (in the
    # parallel projection the same place in the picture; the bubbles are in the water, the foam
    # in its surface)
    for p in readers:
        if kinds[p] == "diffuse":
            moved = pv.Transform(Input=readers[p])
            moved.Transform = "Transform"
            moved.Transform.Translate = list(2 * max(extent) * np.asarray(toward))
            sources[p] = moved

    # the diffuse particles' colours: one a type (categories, with a legend)
    type_lut = pv.GetColorTransferFunction("type")
    type_lut.InterpretValuesAsCategories = 1
    type_lut.Annotations = sum(([str(k), DIFFUSE_TYPES[k][0]] for k in range(3)), [])
    type_lut.IndexedColors = sum((c for _, c in DIFFUSE_TYPES), [])

    fluid_opacity = args["fluidOpacity"]

    written = []
    for field in args["fields"]:
        for t in times:
            for r in sources.values():
                pv.Hide(r, view)
            for f in args["fields"] + ["type"]:  # the colour bar of this field only
                pv.GetScalarBar(pv.GetColorTransferFunction(f), view).Visibility = 0
            has_diffuse = any(kinds[p] == "diffuse" for _, p in drawn(t))
            for block, path in drawn(t):
                kind = kinds[path]
                display = pv.Show(sources[path], view)
                display.Specular = 0
                if kind == "surface":
                    display.SetRepresentationType("Surface")
                    display.ColorArrayName = ["POINTS", ""]
                    display.AmbientColor = display.DiffuseColor = [0.55, 0.75, 1.0]
                    display.Opacity = args["surfaceOpacity"]
                    display.LineWidth = 2
                    continue
                display.SetRepresentationType("Points")
                display.PointSize = point_size
                display.RenderPointsAsSpheres = 0  # flat squares of about one spacing: the fluid reads as a body
                if kind == "fluid":
                    display.Opacity = fluid_opacity
                    vector = readers[path].PointData[field].GetNumberOfComponents() > 1
                    pv.ColorBy(display, ("POINTS", field, "Magnitude") if vector else ("POINTS", field))
                    lut = pv.GetColorTransferFunction(field)
                    lut.ApplyPreset("Turbo" if field != "pressure" else "Cool to Warm", True)
                    lut.RescaleTransferFunction(*ranges[field])
                    try:
                        lut.AutomaticRescaleRangeMode = "Never"
                    except AttributeError:
                        pass
                    display.SetScalarBarVisibility(view, fluid_opacity > 0)
                    bar = pv.GetScalarBar(lut, view)
                    bar.Title = ("speed" if field == "velocity" else "%s magnitude" % field if vector else field) + (" [%s]" % units[field] if field in units else "")
                    bar.ComponentTitle = ""
                    bar.TitleColor = bar.LabelColor = [0, 0, 0]
                    bar.WindowLocation = "Any Location"
                    bar.Position = [0.85, 0.36 if has_diffuse else 0.06]
                    bar.ScalarBarLength = 0.42 if has_diffuse else 0.72
                    bar.HorizontalTitle = 1
                    bar.RangeLabelFormat = bar.LabelFormat = "%.3g"
                    bar.TitleFontSize = bar.LabelFontSize = 14
                    bar.Visibility = 1 if fluid_opacity > 0 else 0  # no colour bar for an invisible fluid
                elif kind == "diffuse":
                    # squares a little smaller than the fluid's (ParaView 5.11 draws points as
                    # spheres behind everything in a parallel projection)
                    display.PointSize = max(3.0, 0.9 * spacing * pixels_per_metre)
                    if readers[path].GetDataInformation().GetNumberOfPoints():
                        pv.ColorBy(display, ("POINTS", "type"))
                        display.LookupTable = type_lut
                    bar = pv.GetScalarBar(type_lut, view)
                    bar.Title = "diffuse"
                    try:
                        bar.DrawBackground = 1  # light grey: the foam's swatch is white
                        bar.BackgroundColor = [0.8, 0.8, 0.8, 1.0]
                    except AttributeError:
                        pass
                    bar.ComponentTitle = ""
                    bar.TitleColor = bar.LabelColor = [0, 0, 0]
                    bar.WindowLocation = "Any Location"
                    bar.Position = [0.85, 0.04]
                    bar.ScalarBarLength = 0.24
                    bar.HorizontalTitle = 1
                    bar.TitleFontSize = bar.LabelFontSize = 14
                    bar.Visibility = 1
                else:
                    display.ColorArrayName = ["POINTS", ""]
                    display.AmbientColor = display.DiffuseColor = [0.55, 0.55, 0.55]
            title = "%s   t = %s s" % (name, t) + ("   " + field if fluid_opacity > 0 else "")
            if t in diffuse_counts:
                title += "   (%s)" % ", ".join("%d %s" % (n, kind) for n, (kind, _) in zip(diffuse_counts[t], DIFFUSE_TYPES))
            label = pv.Text(Text=title)
            text = pv.Show(label, view)
            text.Color = [0, 0, 0]
            text.FontSize = 14
            text.WindowLocation = "Upper Left Corner"
            view.CameraParallelProjection = 1
            if three_d:
                view.CameraPosition = list(camera_centre + 10 * max(extent) * toward)
                view.CameraFocalPoint = list(camera_centre)
                view.CameraViewUp = list(screen_up)
            else:
                view.InteractionMode = "2D"
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
