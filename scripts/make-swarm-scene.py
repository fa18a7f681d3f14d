#!/usr/bin/env python3
"""Writes a benchmark scene into OUT_DIR: swarm.json, 1,000 instances of one 1,280-triangle
icosphere (icosphere.obj; 1.3 million triangles in all) moving in random directions at up to
0.9c, the swarm of the throughput and real-time benchmarks. Measure with
    lightcone view OUT_DIR/swarm.json --benchmark 300 [--width 1920 --height 1080]"""
import json
import math
import os
import random
import sys

if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
    print(__doc__)
    print("usage: make-swarm-scene.py OUT_DIR")
    sys.exit(0 if len(sys.argv) == 2 else 2)
out = sys.argv[1]
os.makedirs(out, exist_ok=True)

# An icosahedron subdivided three times, on the unit sphere.
t = (1 + 5 ** 0.5) / 2
vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
            (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
def unit(p):
    n = math.sqrt(sum(x * x for x in p))
    return tuple(x / n for x in p)
vertices = [unit(p) for p in vertices]
faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
for _ in range(3):
    midpoints, finer = {}, []
    def middle(a, b):
        key = (min(a, b), max(a, b))
        if key not in midpoints:
            vertices.append(unit([(vertices[a][i] + vertices[b][i]) / 2 for i in range(3)]))
            midpoints[key] = len(vertices) - 1
        return midpoints[key]
    for a, b, c in faces:
        ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
        finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    faces = finer
with open(os.path.join(out, "icosphere.obj"), "w") as f:
    f.writelines("v %.6f %.6f %.6f\n" % v for v in vertices)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in faces)

random.seed(42)
objects = []
for i in range(1000):
    d = [random.uniform(-1, 1) for _ in range(3)]
    n = math.sqrt(sum(x * x for x in d)) or 1
    speed = 0.9 * abs(random.uniform(-1, 1))
    objects.append({
        "name": "body-%d" % i,
        "shape": {"mesh": {"file": "icosphere.obj"}},
        "position": [round(random.uniform(-1, 1) * 40, 4), round(random.uniform(-1, 1) * 22, 4),
                     round(-30 + random.uniform(-1, 1) * 25, 4)],
        "velocity": [round(x / n * speed, 6) for x in d],
        "scale": 1.2,
        "material": {"color": [0.8, 0.6, 0.3]},
    })
scene = {"camera": {"position": [0, 0, 0], "fov": 70, "width": 1920, "height": 1080},
         "objects": objects, "sky": {"color": [0.05, 0.05, 0.1]}}
with open(os.path.join(out, "swarm.json"), "w") as f:
    json.dump(scene, f, indent=1)
print("wrote %s and icosphere.obj (%d triangles each, %d bodies)"
      % (os.path.join(out, "swarm.json"), len(faces), len(objects)))
