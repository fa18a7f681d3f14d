"""The scenes of bench/targets.py's `hole` group (issue 55), each beside the flat scene it is
measured against, written as a user would write them:

  lit-balls-hole.json    25 lit checkered balls of radius 1 about a black hole of mass 1 (on
                         rings of radius 7 to 19, a little above and below its equatorial plane),
                         a point lamp and a sun, shadows on (the default), seen from r = 40 a
                         little above, the hole in view; 640x360, 1 sample, a fixed exposure
  lit-balls-flat.json    the same without the hole
  infall-flat.json       scenes/infall.json's three clocks at rest where their falls start (r =
                         10), the same camera and size, without the hole
  orbit-flat.json        scenes/orbit.json's moon at rest where its orbit has it at time 0, the
                         same camera, sun and size, without the hole
  terrell-hole.json      scenes/terrell.json with a hole of 1e-9 units of mass 866 units away
                         (at (500, 500, 500)): its light bends by some 5e-12 radians, a
                         millionth of a pixel

    python3 bench/hole_scenes.py OUT_DIR     # prints the scenes' paths, one a line
"""

import argparse
import json
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def bundled(name):
    """A bundled scene as a dict (its leading comment lines dropped)."""
    with open(os.path.join(ROOT, "scenes", name)) as f:
        return json.loads("".join(line for line in f if not line.lstrip().startswith("//")))


def lit_balls(hole):
    objects = []
    for i in range(25):
        angle, radius = 0.61 * i, 7 + 0.5 * i
        objects.append({
            "name": f"ball{i}", "shape": {"sphere": {"radius": 1}},
            "position": [round(radius * math.cos(angle), 6), round(1.5 * math.sin(1.7 * i), 6),
                         round(radius * math.sin(angle), 6)],
            "material": {"checker": {"size": 0.4, "colors": [[0.9, 0.8, 0.6], [0.3, 0.4, 0.7]]},
                         "unlit": False}})
    scene = {
        "camera": {"position": [0, 6, 40], "forward": [0, -0.15, -1], "fov": 45,
                   "width": 640, "height": 360, "samples": 1},
        "objects": objects,
        "lights": [
            {"name": "lamp", "type": "point", "position": [-14, 10, 6], "intensity": 300,
             "color": [1, 0.9, 0.8]},
            {"name": "sun", "type": "directional", "direction": [-1, -0.3, -0.2],
             "irradiance": 2}],
        "sky": {"color": [0.02, 0.02, 0.04]},
        "render": {"exposure": 0, "tonemap": "filmic"}}
    if hole:
        scene["black_hole"] = {"mass": 1}
    return scene


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def infall_flat():
    scene = bundled("infall.json")
    del scene["black_hole"]
    for o in scene["objects"]:
        fall = o.pop("motion")["fall"]
        o["position"] = [fall["from"] * x for x in unit(fall["direction"])]
    return scene


def orbit_flat():
    scene = bundled("orbit.json")
    del scene["black_hole"]
    for o in scene["objects"]:
        orbit = o.pop("motion")["orbit"]
        # Where it is at time 0: R (cos(phase) a + sin(phase) b), a = x, b = y x a = -z
        # (docs/scene-format.md).
        phase = math.radians(orbit["phase"])
        o["position"] = [orbit["radius"] * math.cos(phase), 0, -orbit["radius"] * math.sin(phase)]
    return scene


def terrell_hole():
    scene = bundled("terrell.json")
    scene["black_hole"] = {"mass": 1e-9, "position": [500, 500, 500]}
    return scene


SCENES = {"lit-balls-hole.json": lambda: lit_balls(True),
          "lit-balls-flat.json": lambda: lit_balls(False),
          "infall-flat.json": infall_flat, "orbit-flat.json": orbit_flat,
          "terrell-hole.json": terrell_hole}


def write_hole_scenes(folder):
    """Writes every scene into `folder`; {name: path}."""
    os.makedirs(folder, exist_ok=True)
    paths = {}
    for name, make in SCENES.items():
        paths[name] = os.path.join(folder, name)
        with open(paths[name], "w") as f:
            json.dump(make(), f, indent=1)
            f.write("\n")
    return paths


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out_dir")
    for path in write_hole_scenes(parser.parse_args().out_dir).values():
        print(path)
