#!/usr/bin/env python3
"""Writes bench/testbeds/arch.obj, the mesh of bench/testbeds/arch.json: a wall 0.6 m thick with a
doorway through it, on a floor and before a back wall, lit from the camera's side. Its convex
edges (the wall's face against the doorway's jambs and lintel, a face seen with a surface just
behind it) are those where the footprint estimators lose light on the benchmark scenes
(docs/accuracy.md, "A clean convex edge: the arch"), in a scene small enough for PoCL to path
trace a reference in a minute. Run from anywhere: python3 bench/testbeds/make_arch.py. Metres; each
box closed; shading is two-sided."""
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

with open(os.path.join(HERE, "arch.obj"), "w") as f:
    f.write("# bench/testbeds/make_arch.py writes this file\no arch\nusemtl grey\n")
    f.writelines("v %g %g %g\n" % v for v in vertices)
    f.writelines("f %d %d %d\n" % t for t in faces)
