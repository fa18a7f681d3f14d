"""The grid of bench/bench_throughput.cpp's case 0 as a scene file, written as a user would
write it (no `render` section: the renderer's defaults), so that the program's whole render of
it can be timed against raw Embree on the same triangles.

A 10 x 10 grid of unit UV spheres (the benchmark's uv_sphere(71, 72), 10,080 triangles, one
shared OBJ), seen 2.5 apart at distance 20 by a camera at rest at the origin, fov 70, 1920 x
1080, 1 sample; `moving`: every sphere at 0.9c along x, placed where the camera sees it as the
benchmark places it.

    python3 bench/grid_scene.py OUT_DIR [--moving]     # prints the scene's path
"""

import argparse
import json
import math
import os

STACKS, SLICES = 71, 72
MESH_FILE = "uv_sphere.obj"


def uv_sphere_obj():
    """The benchmark's UV sphere of radius 1 as OBJ text: `STACKS` rings of `SLICES` quads, two
    triangles each, the poles' degenerate ones dropped; positions at full double precision."""
    lines = []
    for i in range(STACKS + 1):
        theta = math.pi * i / STACKS
        for j in range(SLICES + 1):
            phi = 2 * math.pi * j / SLICES
            x, y, z = math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)
            lines.append(f"v {x!r} {y!r} {z!r}")

    def at(i, j):  # 1-based, as OBJ counts
        return i * (SLICES + 1) + j + 1

    for i in range(STACKS):
        for j in range(SLICES):
            if i > 0:
                lines.append(f"f {at(i, j)} {at(i + 1, j)} {at(i, j + 1)}")
            if i + 1 < STACKS:
                lines.append(f"f {at(i, j + 1)} {at(i + 1, j)} {at(i + 1, j + 1)}")
    return "\n".join(lines) + "\n"


def grid_scene(moving=False):
    """The scene as a dict: the camera at rest at the origin looking along -z, the spheres'
    origins seen at (2.5 col - 11.25, 2.5 row - 11.25, -20)."""
    objects = []
    for i in range(100):
        sphere = {
            "name": f"sphere{i}",
            "shape": {"mesh": {"file": MESH_FILE}},
            "seen_at": [2.5 * (i % 10) - 11.25, 2.5 * (i // 10) - 11.25, -20.0],
        }
        if moving:
            sphere["velocity"] = [0.9, 0, 0]
        objects.append(sphere)
    return {
        "camera": {"position": [0, 0, 0], "fov": 70, "width": 1920, "height": 1080, "samples": 1},
        "objects": objects,
    }


def write_grid_scene(folder, moving=False):
    """Writes the grid's scene and its mesh into `folder` (created if missing); returns the
    scene's path."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, MESH_FILE), "w") as f:
        f.write(uv_sphere_obj())
    path = os.path.join(folder, "grid-moving.json" if moving else "grid.json")
    with open(path, "w") as f:
        json.dump(grid_scene(moving), f, indent=1)
    return path


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir")
    parser.add_argument("--moving", action="store_true", help="every sphere at 0.9c along x")
    args = parser.parse_args()
    print(write_grid_scene(args.out_dir, args.moving))
