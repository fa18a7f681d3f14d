#!/usr/bin/env python3
"""Writes rocket.json: a rocket accelerating from rest past a row of clocks, seen from on board.
The output is committed so that users need no Python."""
import json
import os
import sys

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    print("usage: generate_rocket.py   (writes rocket.json beside this script)")
    sys.exit(0)
os.chdir(os.path.dirname(os.path.abspath(__file__)))

clocks = [{
    "name": f"clock{i}",
    "shape": {"box": {"size": [1.8, 1.8, 0.1]}},
    "position": [x, 0.4, -4],
    "material": {"clock": {"period": 4, "colors": [[0.95, 0.93, 0.85], [0.1, 0.1, 0.12]]}},
} for i, x in enumerate(range(-10, 61, 3))]
scene = {
    "camera": {
        "position": [0, 0, 0], "proper_time": 2,
        "motion": {"phases": [{"duration": 8, "acceleration": [0.5, 0, 0]}]},
        "forward": [1, 0, -0.8], "fov": 90, "width": 960, "height": 540, "samples": 4,
    },
    "objects": clocks + [{
        "name": "ground",
        "shape": {"plane": {"size": [200, 30]}},
        "position": [30, -1.5, -6],
        "material": {"checker": {"size": 1.5, "colors": [[0.12, 0.12, 0.13], [0.24, 0.24, 0.26]]}},
    }],
    "sky": {"grid": {"spacing": 15}},
    }
HEADER = """\
// A rocket accelerating from rest at proper acceleration 0.5 (in units of c^2 per length) past
// a row of clocks, 3 apart and synchronised in their own frame, each turning once every 4 units
// of their time. The camera rides the rocket: at its proper time tau (camera.proper_time) it
// moves at tanh(0.5 tau). Aberration crowds the clocks ahead together, the searchlight
// brightens them, and each shows an earlier time the farther away it is; their hands bend,
// because each point of a dial is seen at its own emission time. Written by generate_rocket.py.
"""
with open("rocket.json", "w") as out:
    out.write(HEADER + json.dumps(scene, indent=1) + "\n")
