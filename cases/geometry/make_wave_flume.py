#!/usr/bin/env python3
"""Writes the STL geometry of the wave-flume cases (wave_flume3d/2d.yaml, caisson_regular2d.yaml).

    python3 cases/geometry/make_wave_flume.py            # writes the STLs next to this script
    python3 cases/geometry/make_wave_flume.py --out DIR  # ... into DIR
    python3 cases/geometry/make_wave_flume.py --check    # only checks the existing files

Two closed, outward-oriented ASCII STL solids, both prisms: a cross-section in the x-z plane
(x along the flume, z up) extruded across the flume width (y):

  flume_beach.stl  the flume bed, in metres and in place: a 1:10 foreshore ramp whose toe is at
                   x = 1.2 m, rising 0.1 m to a flat shelf at x = 2.2 m that runs to the end
                   wall at x = 4.0 m; it spans the full 0.3 m width (y = 0 .. 0.3).
  caisson.stl      a composite breakwater, in millimetres and in its own coordinates (origin at
                   the seaward toe, as a CAD export would be): a rubble-mound berm 500 mm long
                   and 60 mm high with 1:1.5 slopes, carrying a caisson block 200 mm long and
                   240 mm high (crest 300 mm above the berm's base), 300 mm wide. The case
                   files place it with scale 0.001 and translate [2.6, 0, 0.1], on the shelf.
  caisson_vertical.stl  a plain vertical caisson (no mound) for cases/caisson_regular2d.yaml,
                   in metres, origin at its seaward bottom edge: 0.3 m long, 0.6 m high,
                   0.3 m wide; the case places it with translate.

The flume itself (4.0 x 0.3 x 0.5 m, still water 0.3 m deep) is a box in the case files.

After writing, each file is read back and checked: every edge is shared by exactly two faces
with opposite directions (closed and consistently oriented), no face is degenerate, and the
enclosed volume (the sum of signed tetrahedra) is positive (outward normals) and equals the
cross-section area times the width. Any failure exits with an error. Standard library only.
"""

import argparse
import math
import os
import sys

# --- geometry -------------------------------------------------------------------------------

FLUME_LENGTH = 4.0  # m
FLUME_WIDTH = 0.3  # m

# Flume bed: (x, z) in metres, counter-clockwise.
BEACH_SECTION = [
    (1.2, 0.0),  # toe of the 1:10 ramp
    (FLUME_LENGTH, 0.0),
    (FLUME_LENGTH, 0.1),  # shelf at the end wall
    (2.2, 0.1),  # top of the ramp: 1.0 m run, 0.1 m rise
]

# Composite breakwater: (x, z) in millimetres, counter-clockwise, origin at the seaward toe.
CAISSON_SECTION = [
    (0.0, 0.0),  # seaward toe of the berm
    (500.0, 0.0),  # landward toe
    (410.0, 60.0),  # landward berm slope, 1:1.5
    (350.0, 60.0),  # landward heel of the caisson
    (350.0, 300.0),  # caisson crest, landward
    (150.0, 300.0),  # caisson crest, seaward
    (150.0, 60.0),  # seaward face meets the berm
    (90.0, 60.0),  # seaward berm slope, 1:1.5
]
CAISSON_WIDTH_MM = 300.0

# Vertical caisson on a flat bed: (x, z) in metres, counter-clockwise, origin at the seaward
# bottom edge (the face the waves hit is x = 0).
VERTICAL_CAISSON_SECTION = [(0.0, 0.0), (0.3, 0.0), (0.3, 0.6), (0.0, 0.6)]
VERTICAL_CAISSON_WIDTH = 0.3  # m


class GeometryError(Exception):
    pass


def polygon_area(section):
    """Signed area of an (x, z) polygon: > 0 when counter-clockwise."""
    n = len(section)
    return 0.5 * sum(
        section[i][0] * section[(i + 1) % n][1] - section[(i + 1) % n][0] * section[i][1]
        for i in range(n)
    )


def cross2(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def triangulate(section):
    """Ear clipping of a simple counter-clockwise polygon; returns index triples (CCW)."""
    if polygon_area(section) <= 0.0:
        raise GeometryError("section must be counter-clockwise with non-zero area")
    remaining = list(range(len(section)))
    triangles = []
    while len(remaining) > 3:
        for k in range(len(remaining)):
            i, j, l = remaining[k - 1], remaining[k], remaining[(k + 1) % len(remaining)]
            a, b, c = section[i], section[j], section[l]
            if cross2(a, b, c) <= 0.0:  # reflex or flat corner: not an ear
                continue
            inside = False
            for m in remaining:
                if m in (i, j, l):
                    continue
                p = section[m]
                if cross2(a, b, p) >= 0.0 and cross2(b, c, p) >= 0.0 and cross2(c, a, p) >= 0.0:
                    inside = True
                    break
            if not inside:
                triangles.append((i, j, l))
                del remaining[k]
                break
        else:
            raise GeometryError("ear clipping found no ear: is the section simple?")
    triangles.append(tuple(remaining))
    return triangles


def prism(section, y0, y1):
    """Triangles (3 points each) of the closed prism: `section` (x, z), CCW, from y0 to y1.

    In right-handed (x, y, z), a polygon counter-clockwise in the (x, z) plane has normal -y, so
    the cap at y0 keeps the polygon's order and the cap at y1 reverses it. A side quad on edge
    a -> b has outward normal (dz, 0, -dx).
    """
    tris = []
    for i, j, k in triangulate(section):
        a, b, c = section[i], section[j], section[k]
        tris.append(((a[0], y0, a[1]), (b[0], y0, b[1]), (c[0], y0, c[1])))  # normal -y
        tris.append(((a[0], y1, a[1]), (c[0], y1, c[1]), (b[0], y1, b[1])))  # normal +y
    n = len(section)
    for i in range(n):
        a, b = section[i], section[(i + 1) % n]
        a0, b0 = (a[0], y0, a[1]), (b[0], y0, b[1])
        a1, b1 = (a[0], y1, a[1]), (b[0], y1, b[1])
        tris.append((a0, b1, b0))
        tris.append((a0, a1, b1))
    return tris


# --- STL writing and reading ----------------------------------------------------------------


def sub(u, v):
    return (u[0] - v[0], u[1] - v[1], u[2] - v[2])


def cross(u, v):
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def unit_normal(tri):
    n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]))
    length = math.sqrt(dot(n, n))
    if length == 0.0:
        raise GeometryError("degenerate triangle %r" % (tri,))
    return (n[0] / length, n[1] / length, n[2] / length)


def fmt(x):
    s = "%.9g" % x
    return "0" if s == "-0" else s


def write_stl(path, name, triangles):
    # ASCII STL has no comments, and some readers split the file into words, so the solid line
    # holds the name only.
    with open(path, "w", newline="\n") as f:
        f.write("solid %s\n" % name)
        for tri in triangles:
            nx, ny, nz = unit_normal(tri)
            f.write("  facet normal %s %s %s\n" % (fmt(nx), fmt(ny), fmt(nz)))
            f.write("    outer loop\n")
            for v in tri:
                f.write("      vertex %s %s %s\n" % (fmt(v[0]), fmt(v[1]), fmt(v[2])))
            f.write("    endloop\n")
            f.write("  endfacet\n")
        f.write("endsolid %s\n" % name)


def read_stl(path):
    """Facets of an ASCII STL file: a list of (normal, (v0, v1, v2))."""
    facets = []
    normal, loop = None, []
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            words = line.split()
            if not words:
                continue
            if words[0] == "facet":
                normal, loop = tuple(float(w) for w in words[2:5]), []
            elif words[0] == "vertex":
                loop.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "endfacet":
                if normal is None or len(loop) != 3:
                    raise GeometryError("%s:%d: malformed facet" % (path, lineno))
                facets.append((normal, tuple(loop)))
                normal = None
    if not facets:
        raise GeometryError("%s: no facets" % path)
    return facets


# --- checks ---------------------------------------------------------------------------------


def check_solid(path, expected_volume):
    """Fails unless the STL at `path` is a closed, consistently outward-oriented solid."""
    facets = read_stl(path)
    directed = {}
    volume = 0.0
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for index, (normal, tri) in enumerate(facets):
        if len(set(tri)) != 3:
            raise GeometryError("%s: facet %d repeats a vertex" % (path, index))
        n = unit_normal(tri)
        if dot(n, normal) < 0.999:
            raise GeometryError(
                "%s: facet %d: stored normal %r disagrees with its vertex order %r"
                % (path, index, normal, n)
            )
        for k in range(3):
            edge = (tri[k], tri[(k + 1) % 3])
            if edge in directed:
                raise GeometryError(
                    "%s: edge %r -> %r is used twice in the same direction (facets %d and %d): "
                    "inconsistent orientation" % (path, edge[0], edge[1], directed[edge], index)
                )
            directed[edge] = index
            for d in range(3):
                lo[d] = min(lo[d], tri[k][d])
                hi[d] = max(hi[d], tri[k][d])
        volume += dot(tri[0], cross(tri[1], tri[2])) / 6.0
    for (a, b), index in directed.items():
        if (b, a) not in directed:
            raise GeometryError(
                "%s: edge %r -> %r of facet %d has no opposite edge: the surface is open "
                "(every edge must be shared by exactly two faces)" % (path, a, b, index)
            )
    if not volume > 0.0:
        raise GeometryError(
            "%s: enclosed volume %g <= 0: the normals point inwards" % (path, volume)
        )
    if abs(volume - expected_volume) > 1e-9 * max(1.0, expected_volume):
        raise GeometryError(
            "%s: enclosed volume %.12g, expected %.12g" % (path, volume, expected_volume)
        )
    return len(facets), volume, lo, hi


# --- main -----------------------------------------------------------------------------------


SOLIDS = [
    # file, solid name, section, y0, y1, unit, description
    (
        "flume_beach.stl",
        "flume_beach",
        BEACH_SECTION,
        0.0,
        FLUME_WIDTH,
        "m",
        "1:10 foreshore ramp (x 1.2-2.2 m) and 0.1 m shelf to x 4.0 m, 0.3 m wide; metres, in place",
    ),
    (
        "caisson.stl",
        "caisson",
        CAISSON_SECTION,
        0.0,
        CAISSON_WIDTH_MM,
        "mm",
        "caisson block on a rubble-mound berm, 300 mm wide; millimetres, origin at the seaward toe",
    ),
    (
        "caisson_vertical.stl",
        "caisson_vertical",
        VERTICAL_CAISSON_SECTION,
        0.0,
        VERTICAL_CAISSON_WIDTH,
        "m",
        "vertical caisson 0.3 m long, 0.6 m high, 0.3 m wide; metres, origin at the seaward bottom edge",
    ),
]


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=here, help="output folder (default: this script's)")
    parser.add_argument("--check", action="store_true", help="only check the existing files")
    args = parser.parse_args(argv)

    try:
        for file, name, section, y0, y1, unit, description in SOLIDS:
            path = os.path.join(args.out, file)
            if not args.check:
                write_stl(path, name, prism(section, y0, y1))
            expected = polygon_area(section) * (y1 - y0)
            faces, volume, lo, hi = check_solid(path, expected)
            print(
                "%s (%s): %d faces, closed and outward, volume %.6g %s^3, bounds [%s] - [%s] %s"
                % (
                    path,
                    description,
                    faces,
                    volume,
                    unit,
                    ", ".join(fmt(v) for v in lo),
                    ", ".join(fmt(v) for v in hi),
                    unit,
                )
            )
    except (GeometryError, OSError, ValueError) as e:
        print("make_wave_flume.py: error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
