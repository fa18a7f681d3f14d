#!/usr/bin/env python3
"""Writes uv-grid.png and texture-mapping.json: a test texture whose orientation reads at a
glance, and a scene that puts it on a sphere, a box and a plane, for the picture of how each
shape maps a texture (docs/scene-format.md, "Texture coordinates"). The texture's quadrants
are red (top left, u < 0.5 and v < 0.5), green (top right), blue (bottom left) and yellow
(bottom right), with white lines every eighth and a white bar along its top edge (v = 0).
The outputs are committed: users need no Python.

usage: generate_uv_grid.py   (writes both files beside this script)"""
import json
import os
import struct
import sys
import zlib

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0)
os.chdir(os.path.dirname(os.path.abspath(__file__)))

SIZE = 256
QUADRANTS = {(0, 0): (200, 40, 40), (1, 0): (40, 170, 60), (0, 1): (50, 70, 200),
             (1, 1): (220, 190, 40)}


def texel(x, y):
    if y < SIZE // 16 or x % (SIZE // 8) < 3 or y % (SIZE // 8) < 3:
        return (240, 240, 240)
    return QUADRANTS[(2 * x // SIZE, 2 * y // SIZE)]


def png(width, height, pixel):
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y))
                    for y in range(height))
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data +
                                struct.pack(">I", zlib.crc32(kind + data)))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


with open("uv-grid.png", "wb") as out:
    out.write(png(SIZE, SIZE, texel))

scene = {
    "camera": {"position": [5, 3.6, 5.5], "forward": [-5, -2.8, -5.5], "fov": 55, "width": 960,
               "height": 540, "samples": 4},
    "objects": [
        {"name": "sphere", "shape": {"sphere": {"radius": 1.2}}, "position": [-2, 1.2, 0],
         "material": {"texture": "uv-grid.png"}},
        {"name": "box", "shape": {"box": {"size": [2, 2, 2]}}, "position": [1.6, 1, 0],
         "material": {"texture": "uv-grid.png"}},
        {"name": "floor", "shape": {"plane": {"size": [10, 8]}}, "position": [0, 0, -1],
         "material": {"texture": "uv-grid.png"}},
    ],
    "sky": {"color": [0.05, 0.05, 0.07]},
    "render": {"exposure": 0},
}
HEADER = """\
// How each shape maps a texture: uv-grid.png (red top left, green top right, blue bottom left,
// yellow bottom right, a white bar along its top edge v = 0) on a sphere, a box and a plane,
// all at rest. Written by generate_uv_grid.py; see docs/scene-format.md, "Texture coordinates".
"""
with open("texture-mapping.json", "w") as out:
    out.write(HEADER + json.dumps(scene, indent=1) + "\n")
