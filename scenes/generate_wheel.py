#!/usr/bin/env python3
"""Writes wheel.obj: a spoked wheel of radius 1 in the x-y plane (axle along z), 0.12 thick: a
rim from radius 0.86 to 1, a hub of radius 0.16 and eight spokes. wheel.json rolls it past the
camera at 0.8c. The output is committed so that users need no Python."""
import math
import os
import sys

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    print("usage: generate_wheel.py   (writes wheel.obj beside this script)")
    sys.exit(0)
os.chdir(os.path.dirname(os.path.abspath(__file__)))

HALF = 0.06  # half the thickness
vertices, faces = [], []


def vertex(x, y, z):
    vertices.append((x, y, z))
    return len(vertices)  # OBJ indices start at 1


def quad(a, b, c, d):
    faces.append((a, b, c))
    faces.append((a, c, d))


def annulus(inner, outer, segments):
    """A flat ring, closed at both faces and at both edges."""
    rings = []
    for r in (inner, outer):
        for z in (-HALF, HALF):
            rings.append([vertex(r * math.cos(2 * math.pi * i / segments),
                                 r * math.sin(2 * math.pi * i / segments), z)
                          for i in range(segments)])
    in_back, in_front, out_back, out_front = rings
    for i in range(segments):
        j = (i + 1) % segments
        quad(in_front[i], out_front[i], out_front[j], in_front[j])  # front face
        quad(in_back[j], out_back[j], out_back[i], in_back[i])      # back face
        quad(out_back[i], out_back[j], out_front[j], out_front[i])  # outer edge
        quad(in_back[j], in_back[i], in_front[i], in_front[j])      # inner edge


def box(centre, half, angle):
    """A box with half sizes `half`, turned by `angle` about z."""
    c, s = math.cos(angle), math.sin(angle)
    corners = []
    for dx in (-1, 1):
        for dy in (-1, 1):
            for dz in (-1, 1):
                x, y = dx * half[0], dy * half[1]
                corners.append(vertex(centre[0] + c * x - s * y, centre[1] + s * x + c * y,
                                      dz * half[2]))
    v = lambda dx, dy, dz: corners[(dx * 4) + (dy * 2) + dz]
    quad(v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1))
    quad(v(0, 1, 0), v(1, 1, 0), v(1, 0, 0), v(0, 0, 0))
    quad(v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1))
    quad(v(0, 1, 1), v(1, 1, 1), v(1, 1, 0), v(0, 1, 0))
    quad(v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0))
    quad(v(1, 1, 0), v(1, 1, 1), v(1, 0, 1), v(1, 0, 0))


annulus(0.86, 1.0, 96)
annulus(0.04, 0.16, 24)
for k in range(8):
    angle = 2 * math.pi * k / 8
    mid = 0.51
    box((mid * math.cos(angle), mid * math.sin(angle)), (0.36, 0.035, HALF * 0.8), angle)

with open("wheel.obj", "w") as out:
    out.write("# A spoked wheel, written by generate_wheel.py\n")
    for x, y, z in vertices:
        out.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
    for a, b, c in faces:
        out.write(f"f {a} {b} {c}\n")
print(f"wheel.obj: {len(vertices)} vertices, {len(faces)} triangles")
