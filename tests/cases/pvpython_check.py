"""Checks that ParaView reads a Spindrift case collection (.pvd) as expected.

Usage:
    pvpython pvpython_check.py [--blocks N] [--changing BLOCK:ARRAY] <file.pvd> <expectedTimeCount>
            <array1> [array2 ...]

Opens the .pvd with ParaView's PVD reader, checks that it reports exactly
<expectedTimeCount> time steps, then, at every time step, updates the pipeline, fetches the
data and checks that the fluid data set (part 0 of the collection; a multiblock data set when
the case also has walls, part 1) has more than zero points and every named point-data array.
With --blocks N, every time step must hold exactly N data sets with points: one block per
particle system (the fluid, and each wall system, fixed or moving); --may-be-empty NAME (any
number of times) counts the block NAME even when it has no points (a passive system whose
particles are generated later, e.g. diffuse particles). With --changing BLOCK:ARRAY,
the block of that name (a wall system) has the point array at every time step, and its values
at the last time step are not those of the first (a wall's own pressure, following the flow).
Prints one summary line and exits 0; on any failure prints the reasons to stderr and exits 1.
"""

import sys


may_be_empty = []  # --may-be-empty NAME: blocks counted even without points (a passive system not yet seeded)


def fail(messages):
    for m in messages:
        print("pvpython_check: FAILED: " + m, file=sys.stderr)
    sys.exit(1)


def parse_arguments(argv):
    blocks = None
    changing = None
    global may_be_empty
    while len(argv) > 2 and argv[1] in ("--blocks", "--changing", "--may-be-empty"):
        if argv[1] == "--blocks":
            blocks = int(argv[2])
        elif argv[1] == "--may-be-empty":
            may_be_empty.append(argv[2])
        else:
            changing = tuple(argv[2].split(":", 1))
        argv = argv[:1] + argv[3:]
    if len(argv) < 4:
        fail(["usage: pvpython pvpython_check.py <file.pvd> <expectedTimeCount> "
              "<array1> [array2 ...]"])
    try:
        expected = int(argv[2])
    except ValueError:
        fail(["expectedTimeCount must be an integer, got '%s'" % argv[2]])
    return argv[1], expected, argv[3:], blocks, changing


def named_block(data, name):
    """The leaf whose block name is 'name' (a part's name in the .pvd), or None."""
    for path, block in leaves(data):
        if path.split("/")[0].split(":", 1)[-1] == name:
            return block
    return None


def leaves(data, path=""):
    """(path, data set) for every non-composite data set inside 'data' (itself if simple)."""
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkMultiBlockDataSet
    if data is None:
        return []
    if not isinstance(data, vtkMultiBlockDataSet):
        return [(path, data)]
    found = []
    for i in range(data.GetNumberOfBlocks()):
        name = str(i)
        if data.HasMetaData(i):
            meta = data.GetMetaData(i)
            if meta.Has(vtkCompositeDataSet.NAME()):
                name = "%d:%s" % (i, meta.Get(vtkCompositeDataSet.NAME()))
        found += leaves(data.GetBlock(i), path + "/" + name if path else name)
    return found


def fluid_block(data):
    """The fluid part: the data itself for a single part, else the first leaf of block 0."""
    all_leaves = leaves(data)
    if not all_leaves:
        return None, "no data set at all"
    if len(all_leaves) == 1:
        return all_leaves[0][1], all_leaves[0][0] or "(single data set)"
    for path, block in all_leaves:  # part 0 of the collection comes first
        if path.split("/")[0].split(":")[0] == "0":
            return block, path
    return all_leaves[0][1], all_leaves[0][0]


def main(argv):
    pvd, expected, arrays, blocks, changing = parse_arguments(argv)

    import os
    if not os.path.isfile(pvd):
        fail(["no such file: '%s'" % pvd])

    from paraview import servermanager
    from paraview.simple import PVDReader
    from vtkmodules.vtkCommonDataModel import vtkDataObject

    reader = PVDReader(FileName=pvd)
    times = reader.TimestepValues
    if times is None:
        times = []
    elif isinstance(times, (int, float)):
        times = [times]
    else:
        times = list(times)

    errors = []
    if len(times) != expected:
        errors.append("'%s' has %d time steps (%s), expected %d"
                      % (pvd, len(times), ", ".join("%g" % t for t in times), expected))

    total_points = 0
    changing_values = []  # the --changing array's values at each time step
    for t in times:
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        if data is None:
            errors.append("time %g: no data fetched" % t)
            continue
        info = data.GetInformation()
        if info.Has(vtkDataObject.DATA_TIME_STEP()):
            got = info.Get(vtkDataObject.DATA_TIME_STEP())
            if abs(got - t) > 1e-12 * max(1.0, abs(t)):
                errors.append("time %g: fetched data is for time %g" % (t, got))
        if blocks is not None:
            filled = [path for path, block in leaves(data)
                      if hasattr(block, "GetNumberOfPoints") and
                      (block.GetNumberOfPoints() > 0 or path.split("/")[0].split(":")[-1] in may_be_empty)]
            if len(filled) != blocks:
                errors.append("time %g: %d blocks with points (%s), expected %d"
                              % (t, len(filled), ", ".join(filled), blocks))
        if changing is not None:
            block = named_block(data, changing[0])
            array = block.GetPointData().GetArray(changing[1]) if block is not None else None
            if array is None:
                errors.append("time %g: no block '%s' with a point array '%s' (blocks: %s)"
                              % (t, changing[0], changing[1], ", ".join(p for p, _ in leaves(data))))
            else:
                changing_values.append([array.GetValue(i) for i in range(array.GetNumberOfValues())])
        fluid, where = fluid_block(data)
        if fluid is None or not hasattr(fluid, "GetPointData"):
            errors.append("time %g: no fluid data set in the %s (%s)"
                          % (t, data.GetClassName(), where))
            continue
        n = fluid.GetNumberOfPoints()
        total_points += n
        if n <= 0:
            errors.append("time %g: fluid (%s) has no points" % (t, where))
        point_data = fluid.GetPointData()
        present = [point_data.GetArrayName(i) for i in range(point_data.GetNumberOfArrays())]
        for name in arrays:
            if name not in present:
                errors.append("time %g: fluid (%s) has no point array '%s' (has: %s)"
                              % (t, where, name, ", ".join(present)))

    if changing is not None and len(changing_values) >= 2 and changing_values[0] == changing_values[-1]:
        errors.append("%s of '%s' is the same at the last time step as at the first" % (changing[1], changing[0]))
    if errors:
        fail(errors)
    print("pvpython_check: OK: %s: %d time steps (%s), %d fluid points in all, arrays %s"
          % (pvd, len(times), ", ".join("%g" % t for t in times), total_points,
             ", ".join(arrays)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
