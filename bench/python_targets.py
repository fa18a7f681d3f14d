"""Issue 29's figures for the Python module, in one run:
- render from Python against the library's own render time (RenderStats.seconds, which the
  module returns), street.json at 640x360 and 4 samples, repeated;
- each vectorised kernel against a pure-numpy implementation of the same formula, on 10^6
  directions.

    PYTHONPATH=build/python python3 bench/python_targets.py
"""

import statistics
import sys
import time

import numpy as np

import lightcone as lc
from lightcone import _lightcone

scenes = sys.argv[1] if len(sys.argv) > 1 else "scenes"


def median_time(f, repeat=7):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times), max(times)


# Render: the whole call from Python over the library's render_image time.
scene = lc.load(f"{scenes}/street.json", overrides={"camera.width": 640, "camera.height": 360})
ratios = []
for _ in range(7):
    start = time.perf_counter()
    result = _lightcone.render(scene, "trace", [], 0, 0, "auto", None)
    whole = time.perf_counter() - start
    ratios.append(whole / result["seconds"])
    lc.render(scene, progress=False)  # (the package's path too, for its argument checks)
print(f"render from Python over the library's render time: median {statistics.median(ratios):.4f} "
      f"({min(ratios):.4f} to {max(ratios):.4f}); target <= 1.02")

# Kernels against numpy, 10^6 directions.
rng = np.random.default_rng(1)
n = rng.normal(size=(1_000_000, 3))
n /= np.linalg.norm(n, axis=1, keepdims=True)
beta = np.array([0.3, -0.2, 0.6])


def numpy_doppler(n, be):
    g = 1 / np.sqrt(1 - be @ be)
    return 1 / (g * (1 - n @ be))


def numpy_aberrate(d, b):
    """The photon's 4-momentum (1, -d) boosted by b; the look direction is minus its
    spatial part over its energy."""
    b2 = b @ b
    g = 1 / np.sqrt(1 - b2)
    bd = d @ b  # b.d, so b.k = -b.d
    energy = g * (1 + bd)
    spatial = -d + (((g - 1) * -bd / b2) - g)[:, None] * b
    return -spatial / energy[:, None]


def numpy_doppler_each(n, be, br):
    """The kernel's formula element by element: (k.U_R) / (k.U_E), k = (1, n)."""
    ge = 1 / np.sqrt(1 - np.einsum("ij,ij->i", be, be))
    gr = 1 / np.sqrt(1 - np.einsum("ij,ij->i", br, br))
    return (gr * (1 - np.einsum("ij,ij->i", n, br))) / (ge * (1 - np.einsum("ij,ij->i", n, be)))


each_e = rng.normal(size=(1_000_000, 3)) * 0.3
each_r = rng.normal(size=(1_000_000, 3)) * 0.3
each_e[np.einsum("ij,ij->i", each_e, each_e) >= 0.98] = 0
each_r[np.einsum("ij,ij->i", each_r, each_r) >= 0.98] = 0

for name, ours, theirs in [
    ("doppler_factor, a velocity each", lambda: lc.physics.doppler_factor(n, each_e, each_r),
     lambda: numpy_doppler_each(n, each_e, each_r)),
    ("doppler_factor, one velocity", lambda: lc.physics.doppler_factor(n, beta), lambda: numpy_doppler(n, beta)),
    ("aberrate", lambda: lc.physics.aberrate(n, beta), lambda: numpy_aberrate(n, beta)),
]:
    assert np.allclose(ours(), theirs(), rtol=1e-9, atol=1e-12), name
    t_ours = median_time(ours)[0]
    t_numpy = median_time(theirs)[0]
    print(f"{name} on 10^6 directions: {t_ours * 1e3:.1f} ms against numpy's {t_numpy * 1e3:.1f} ms: "
          f"{t_numpy / t_ours:.2f}x; target >= 3x")
