#!/usr/bin/env python3
"""Writes bench/testbeds/arch.obj, the mesh of bench/testbeds/arch.json: a wall 0.6 m thick with a
doorway through it, on a floor and before a back wall, lit from the camera's side; and
arch-column.obj (arch-column.json), the same with a column of 16 flat facets before the wall.
The wall's face meets the doorway's jambs and lintel at convex edges with a surface just behind
them, and the column's facets turn 22.5 degrees from one to the next: the edges and bends where
the footprint estimators are biased on the benchmark scenes (docs/accuracy.md, "A clean convex
edge: the arch"), in scenes small enough for PoCL to path trace a reference in a minute or two.
Run from anywhere: python3 bench/testbeds/make_arch.py. Metres; the wall's boxes closed; shading
is two-sided."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
vertices, faces = [], []


def quad(a, b, c, d):
    first = len(vertices) + 1
    vertices.extend([a, b, c, d])
    faces.extend([(first, first + 1, first + 2), (first, first + 2, first + 3)])


def box(x0, x1, y0, y1, z0, z1):
    quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))  # front, z = z0
    quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # back
    quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # left
    quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # right
    quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # top
    quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # bottom


quad((-8, 0, -8), (-8, 0, 8), (8, 0, 8), (8, 0, -8))  # the floor
box(-3, -1, 0, 4, 0, 0.6)  # the wall's left pier
box(1, 3, 0, 4, 0, 0.6)  # its right pier
box(-1, 1, 3, 4, 0, 0.6)  # the lintel over the doorway (2 m wide, 3 m high)
quad((-8, 0, 4), (8, 0, 4), (8, 6, 4), (-8, 6, 4))  # the back wall


def write(name):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("# bench/testbeds/make_arch.py writes this file\no arch\nusemtl grey\n")
        f.writelines("v %g %g %g\n" % v for v in vertices)
        f.writelines("f %d %d %d\n" % t for t in faces)


write("arch.obj")
# A column 0.3 m in radius and 3.5 m tall, 16 flat facets (22.5 degrees apart), open at the top.
for i in range(16):
    a0, a1 = 2 * math.pi * i / 16, 2 * math.pi * (i + 1) / 16
    x0, z0 = -1.8 + 0.3 * math.cos(a0), -1.5 + 0.3 * math.sin(a0)
    x1, z1 = -1.8 + 0.3 * math.cos(a1), -1.5 + 0.3 * math.sin(a1)
    quad((x0, 0, z0), (x1, 0, z1), (x1, 3.5, z1), (x0, 3.5, z0))
write("arch-column.obj")
