#!/usr/bin/env python3
"""Writes the mesh files that scenes/ uses (scenes/meshes/), each a closed, outward-oriented
triangle mesh in one of the formats TEM reads:

  hex_ring.obj   the paper's ring (16 segments, hexagonal section), lying flat (axis z)
  cup.stl        a 16-sided cup, hollow, with a bottom (binary STL)
  staple.off     a U-shaped staple, the body of the non-convex pour
  staple.ply     the same staple as ASCII PLY

Run it again to regenerate them: python3 tools/make_meshes.py [OUT_DIR]. The files are small and
committed, so a scene runs without this script.
"""
import math
import struct
import sys
from pathlib import Path


def ring(segments=16, sides=6, radius=0.15, section_radius=0.05):
    """A sides-gon section swept round a segments-gon centre line, as the ring primitive does
    (src/geometry/primitives.cpp): the section lies in the plane through the axis at each centre
    line vertex, its first node pointing radially outward."""
    vertices = []
    for k in range(segments):
        theta = 2 * math.pi * k / segments
        c, s = math.cos(theta), math.sin(theta)
        for j in range(sides):
            phi = 2 * math.pi * j / sides
            r = radius + section_radius * math.cos(phi)
            vertices.append((r * c, r * s, section_radius * math.sin(phi)))
    faces = []
    for k in range(segments):
        for j in range(sides):
            a = k * sides + j
            b = ((k + 1) % segments) * sides + j
            c = ((k + 1) % segments) * sides + (j + 1) % sides
            d = k * sides + (j + 1) % sides
            faces += [(a, b, c), (a, c, d)]
    return vertices, faces


def cup(sides=16, outer=0.1, height=0.12, wall=0.015, bottom=0.015):
    """A hollow prism closed at the bottom: outer wall, rim, inner wall, inner floor, base."""
    inner = outer - wall
    rings = [(outer, 0.0), (outer, height), (inner, height), (inner, bottom)]
    vertices = []
    for r, z in rings:
        for k in range(sides):
            t = 2 * math.pi * k / sides
            vertices.append((r * math.cos(t), r * math.sin(t), z))
    base_centre = len(vertices)
    vertices.append((0.0, 0.0, 0.0))
    floor_centre = len(vertices)
    vertices.append((0.0, 0.0, bottom))
    faces = []

    def at(ring_index, k):
        return ring_index * sides + k % sides

    for k in range(sides):
        # Bands between consecutive rings: outer wall (0-1), rim (1-2), inner wall (2-3).
        for ring_index in range(3):
            a, b = at(ring_index, k), at(ring_index, k + 1)
            c, d = at(ring_index + 1, k + 1), at(ring_index + 1, k)
            faces += [(a, b, c), (a, c, d)]
        faces.append((base_centre, at(0, k + 1), at(0, k)))   # base, seen from below
        faces.append((floor_centre, at(3, k), at(3, k + 1)))  # inner floor, seen from above
    return vertices, faces


def extrusion(loop, cap, height):
    """A prism over a simple polygon (counter-clockwise loop) with the cap's triangles given."""
    n = len(loop)
    vertices = [(x, y, 0.0) for x, y in loop] + [(x, y, height) for x, y in loop]
    faces = [(a, c, b) for a, b, c in cap] + [(a + n, b + n, c + n) for a, b, c in cap]
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, j, j + n), (i, j + n, i + n)]
    return vertices, faces


def staple(unit=0.01, depth=0.01):
    """A U: the square [0, 3]^2 less the slot [1, 2] x [1, 3], extruded by `depth`, centred."""
    loop = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]
    cap = [(0, 1, 4), (0, 4, 5), (1, 2, 3), (1, 3, 4), (0, 5, 6), (0, 6, 7)]
    vertices, faces = extrusion([((x - 1.5) * unit, (y - 1.5) * unit) for x, y in loop], cap, depth)
    return [(x, y, z - depth / 2) for x, y, z in vertices], faces


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        f.write("# written by tools/make_meshes.py\n")
        for v in vertices:
            f.write("v %.17g %.17g %.17g\n" % v)
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def write_off(path, vertices, faces):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(vertices), len(faces)))
        for v in vertices:
            f.write("%.17g %.17g %.17g\n" % v)
        for face in faces:
            f.write("3 %d %d %d\n" % face)


def write_ply(path, vertices, faces):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\ncomment written by tools/make_meshes.py\n")
        f.write("element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
                % len(vertices))
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
        for v in vertices:
            f.write("%.17g %.17g %.17g\n" % v)
        for face in faces:
            f.write("3 %d %d %d\n" % face)


def write_stl_binary(path, vertices, faces):
    with open(path, "wb") as f:
        f.write(b"binary STL written by tools/make_meshes.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(faces)))
        for face in faces:
            a, b, c = (vertices[i] for i in face)
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(struct.pack("<12fH", *(x / length for x in n), *a, *b, *c, 0))


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenes" / "meshes"
    out.mkdir(parents=True, exist_ok=True)
    write_obj(out / "hex_ring.obj", *ring())
    write_stl_binary(out / "cup.stl", *cup())
    write_off(out / "staple.off", *staple())
    write_ply(out / "staple.ply", *staple())
    print("wrote", ", ".join(sorted(p.name for p in out.iterdir())), "in", out)


if __name__ == "__main__":
    main()
