#!/usr/bin/env python3
"""damBreakObstacle3D: sets the case to particle spacing dx = 0.55/N m (N particles over the
water's 0.55 m height; the benchmark's N = 30, as shipped).

    ./setResolution.py N [endTime]

The particles sit on a lattice of whole spacings, so a length that is not a whole number of dx
is rounded (constant/geometry would otherwise move a wall's max face with a warning). The
rounding is chosen here so that the faces that matter stay where the benchmark has them:
- the tank's far wall (x = 3.22, the water's back) and its y = 0 wall are exact; its x = 0 wall
  moves by less than dx/2 (x min = 3.22 - round(3.22/dx) dx), its width is round(1/dx) dx; its
  walls are round(1.5/dx) dx high, not 1 m (WALL_HEIGHT below);
- the water spans round(1.228/dx) dx from the far wall back, the tank's width, 0.55 m high
  (exact at every N that divides 0.55 m into whole spacings: all N here);
- the box's impacted face x = 0.8245 and its mid-width y = 0.4965 are exact; its length,
  width and height are round(size/dx) dx (height round(0.161/dx) dx: its top moves);
- the pressure probes P1-P4 sit 1 mm in front of the impacted face, P5-P8 1 mm above the top
  as this N makes it (tutorials/validation/damBreakColagrossi2D places its wall probes so).
Prints what it set; edits constant/fluidProperties, constant/geometry, system/controlDict.
"""
import os
import re
import sys

TANK = (3.22, 1.0, 1.0)
# The tank's walls are raised to 1.5 m: the water running up the x = 0 wall reaches 1.26 m at
# dx = 0.55/15 (t = 0.97 s) and, over 1 m walls, falls outside the tank and out of the case.
WALL_HEIGHT = 1.5
WATER = (1.228, 0.55)          # length (x), height (z); the water spans the tank's width
BOX_FACE_X, BOX_MID_Y = 0.8245, 0.295 + 0.5 * 0.403
BOX = (0.161, 0.403, 0.161)    # x, y, z
# sensors: P1-P4 on the impacted face at these heights, P5-P8 on the top at these distances
# from that face; both rows 0.176 m from the box's y = 0.295 side (SPHERIC test 2, fig. 7)
SENSOR_HEIGHTS = (0.021, 0.061, 0.101, 0.141)
SENSOR_Y = 0.295 + 0.176
PROBE_OFFSET = 0.001


def fmt(v):
    return ("%.10g" % v) if abs(v) > 1e-12 else "0"


def vec(*v):
    return "(" + " ".join(fmt(x) for x in v) + ")"


def replace(path, pattern, value, count=1):
    with open(path) as fh:
        text = fh.read()
    new, n = re.subn(pattern, lambda m: m.group(1) + value + m.group(2), text, count=count, flags=re.M | re.S)
    if n != count:
        sys.exit("%s: could not set %r (found %d of %d)" % (path, pattern, n, count))
    with open(path, "w") as fh:
        fh.write(new)


def block_entry(block, key):
    """The first 'key ...;' entry after the line naming 'block' (an indented block of constant/geometry)."""
    return r"(^\s*" + block + r"\s*\n\s*\{.*?^\s*" + key + r"\s+)[^;]*(;)"


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    N = int(sys.argv[1])
    if N < 5:
        sys.exit("N = %d: at least 5 particles over the water's height" % N)
    dx = WATER[1] / N
    cells = lambda length: max(1, round(length / dx))
    tank_x0 = TANK[0] - cells(TANK[0]) * dx
    width = cells(TANK[1]) * dx
    height = cells(WALL_HEIGHT) * dx
    water_x0 = TANK[0] - cells(WATER[0]) * dx
    nb = [cells(s) for s in BOX]
    box_lo = (BOX_FACE_X - nb[0] * dx, BOX_MID_Y - 0.5 * nb[1] * dx, 0.0)
    box_hi = (BOX_FACE_X, BOX_MID_Y + 0.5 * nb[1] * dx, nb[2] * dx)

    here = os.path.dirname(os.path.abspath(__file__))
    props = os.path.join(here, "constant", "fluidProperties")
    geometry = os.path.join(here, "constant", "geometry")
    control = os.path.join(here, "system", "controlDict")
    replace(props, r"(^particleSpacing\s+)[^;]*(;)", fmt(dx))
    replace(geometry, block_entry("water", "min"), vec(water_x0, 0, 0))
    replace(geometry, block_entry("water", "max"), vec(TANK[0], width, WATER[1]))
    replace(geometry, block_entry("tank", "min"), vec(tank_x0, 0, 0))
    replace(geometry, block_entry("tank", "max"), vec(TANK[0], width, height))
    replace(geometry, block_entry("obstacle", "min"), vec(*box_lo))
    replace(geometry, block_entry("obstacle", "max"), vec(*box_hi))
    front = " ".join(vec(BOX_FACE_X + PROBE_OFFSET, SENSOR_Y, z) for z in SENSOR_HEIGHTS)
    top = " ".join(vec(BOX_FACE_X - d, SENSOR_Y, box_hi[2] + PROBE_OFFSET) for d in SENSOR_HEIGHTS)
    replace(control, r"(^\s*probeLocations\s+)[^;]*(;)", "(" + front + " " + top + ")")
    if len(sys.argv) == 3:
        replace(control, r"(^endTime\s+)[^;]*(;)", fmt(float(sys.argv[2])))
    print("damBreakObstacle3D at dx = 0.55/%d = %.6g m: tank x %.6g..%.6g, width %.6g; water x %.6g..%.6g "
          "(%d x %d x %d particles); box x %.6g..%.6g, y %.6g..%.6g, top z %.6g"
          % (N, dx, tank_x0, TANK[0], width, water_x0, TANK[0], cells(WATER[0]), cells(TANK[1]), N,
             box_lo[0], box_hi[0], box_lo[1], box_hi[1], box_hi[2]))


if __name__ == "__main__":
    main()
