"""A tour of lightcone from Python (docs/python.md): a plot of the Doppler factor against the
viewing angle, a sweep of the Terrell-Penrose rotation over speed, and a grid of pictures.

    PYTHONPATH=build/python python3 examples/python/tour.py OUT_FOLDER

It writes OUT_FOLDER/python-terrell-sweep.png (and python-doppler.png where matplotlib is
installed; otherwise it prints the plot's numbers)."""

import os
import sys

import numpy as np

import lightcone as lc

here = os.path.dirname(os.path.abspath(__file__))
scenes = os.path.join(here, "..", "..", "scenes")
out = sys.argv[1] if len(sys.argv) > 1 else "."

# 1. The Doppler factor of a source moving at beta, against the angle between its velocity and
#    the line of sight (light travelling toward the camera at the origin).
angles = np.linspace(0, np.pi, 181)
n = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=-1)
speeds = [0.3, 0.6, 0.9]
doppler = {beta: lc.physics.doppler_factor(n, beta_emitter=[beta, 0, 0]) for beta in speeds}
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.5))
    for beta, d in doppler.items():
        ax.semilogy(np.degrees(angles), d, label=f"beta = {beta}")
    ax.set_xlabel("angle between the velocity and the light's direction (degrees)")
    ax.set_ylabel("Doppler factor D")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "python-doppler.png"), dpi=100)
except ImportError:
    for beta, d in doppler.items():
        print(f"beta {beta}: D from {d.min():.3f} (receding) to {d.max():.3f} (approaching)")

# 2. The Terrell-Penrose rotation over speed: terrell.json's ball and crate at four speeds,
#    each picture with its own automatic exposure (the scene's), so that the receding bodies'
#    dimming, D^4, does not hide them.
sweep = []
for beta in [0.0, 0.3, 0.6, 0.9]:
    scene = lc.load(os.path.join(scenes, "terrell.json"),
                    overrides={"camera.width": 320, "camera.height": 180,
                               "objects[0].velocity": [beta, 0, 0],
                               "objects[1].velocity": [beta, 0, 0]})
    sweep.append(lc.render(scene, samples=4, progress=False))
    seen = lc.locate(scene, object="ball", point=[0, 0, 0])
    print(f"beta {beta}: the ball's centre seen with D = {seen['doppler']:.3f}")

# 3. The pictures as a grid, tone-mapped as the program's PNGs are.
grid = np.concatenate([np.concatenate(sweep[:2], axis=1), np.concatenate(sweep[2:], axis=1)],
                      axis=0).view(lc.Image)
with open(os.path.join(out, "python-terrell-sweep.png"), "wb") as f:
    f.write(grid._repr_png_())
print("wrote", os.path.join(out, "python-terrell-sweep.png"))
