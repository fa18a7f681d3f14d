"""The Python module's boundary under hostile input: seeded random mutations of a valid scene
dict, and hostile arguments to every function, each either accepted or refused with the
module's own exceptions (SceneError, TypeError, ValueError, OverflowError) and a message a
person can read; never a crash, a hang, a raw pybind11 or Boost message, or a non-finite
picture. The program's own hostile-input cases are tests/test_hostile_input.cpp and the
libFuzzer harnesses in fuzz/.

Run by ctest (Python.pytest) with LIGHTCONE_SOURCE_DIR the repository."""

import copy
import math
import os
import random
import time

import numpy as np
import pytest

import lightcone as lc

SOURCE = os.environ.get("LIGHTCONE_SOURCE_DIR", ".")
REFUSED = (lc.SceneError, TypeError, ValueError, OverflowError)

BASE = {
    "camera": {"position": [0, 0, 0], "velocity": [0, 0, -0.5], "fov": 40, "width": 16,
               "height": 9, "samples": 1},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [0, 0, -6],
                 "velocity": [0.6, 0, 0], "material": {"color": [0.2, 0.8, 0.3]}}],
    "sky": {"color": [0.1, 0.2, 0.4]},
    "render": {"exposure": 0},
}

# Values a hostile caller hands over where a number, a list, a string or an object belongs.
HOSTILE = [
    float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 5e-324, 2**63, -2**63, 2**64,
    10**400, 0, -1, 1, 0.999999999999, 1.0000001, True, None, "", "x" * 100_000, "\x00\x1b[31m",
    "../../../../etc/passwd", "/dev/zero", [], [1], [1, 2, 3, 4], [[[]]], {}, {"": 1},
    np.float32(0.5), np.float64("nan"), np.int64(2**62), np.uint64(2**64 - 1), np.bool_(True),
    np.array([0.1, 0.2, 0.3]), np.array([[1.0]]), np.array([np.inf, 0, 0]), object(), b"bytes",
    {1: 2}, (0, 0, 0), {"nested": {"deeper": {"deepest": [float("nan")]}}},
]


def _paths(value, prefix=()):
    """Every (path, value) in a dict-and-list document, containers included."""
    yield prefix, value
    if isinstance(value, dict):
        for key, inner in value.items():
            yield from _paths(inner, prefix + (key,))
    elif isinstance(value, list):
        for index, inner in enumerate(value):
            yield from _paths(inner, prefix + (index,))


def _replaced(document, path, value):
    out = copy.deepcopy(document)
    if not path:
        return value
    holder = out
    try:
        for step in path[:-1]:
            holder = holder[step]
        holder[path[-1]] = value
    except (KeyError, IndexError, TypeError):  # an earlier mutation took the path away
        return document
    return out


def _check_message(error):
    text = str(error)
    assert text, f"{type(error).__name__} without a message"
    assert len(text) < 2000, text[:200]
    assert "\x00" not in text and "\x1b" not in text
    lowered = text.lower()
    for raw in ("boost", "pybind11", "incompatible function arguments", "std::"):
        assert raw not in lowered, text


def test_mutated_scenes_are_read_or_refused_by_name():
    rng = random.Random(53)
    paths = [p for p, _ in _paths(BASE)]
    cases = refused = 0
    started = time.monotonic()
    for _ in range(1500):
        document = BASE
        for _ in range(rng.randint(1, 3)):
            document = _replaced(document, rng.choice(paths) if rng.random() < 0.9 else (),
                                 rng.choice(HOSTILE))
        cases += 1
        try:
            scene = lc.Scene.from_dict(document)
        except REFUSED as e:
            refused += 1
            _check_message(e)
            continue
        assert isinstance(scene, lc.Scene)
    assert refused > cases // 2  # the mutations mostly break the scene
    assert time.monotonic() - started < 120


def test_accepted_mutations_render_finite_pictures_or_are_refused():
    rng = random.Random(54)
    numbers = [p for p, v in _paths(BASE) if isinstance(v, (int, float)) and not isinstance(v, bool)]
    rendered = 0
    for _ in range(150):
        path = rng.choice(numbers)
        value = rng.choice([0, -1, 1e-300, 1e300, 0.99999999, -0.99999999, 1e6, 7, 0.5])
        try:
            scene = lc.Scene.from_dict(_replaced(BASE, path, value))
        except REFUSED as e:
            _check_message(e)
            continue
        try:
            image = lc.render(scene, progress=False)
        except (lc.SceneError, RuntimeError) as e:
            _check_message(e)
            continue
        rendered += 1
        assert np.all(np.isfinite(image)), path
    assert rendered > 20


@pytest.mark.parametrize("value", HOSTILE, ids=lambda v: type(v).__name__)
def test_every_function_refuses_hostile_arguments_by_name(value, tmp_path):
    scene = lc.Scene.from_dict(BASE)
    calls = [
        lambda: lc.load(value),
        lambda: lc.load(os.path.join(SOURCE, "scenes", "terrell.json"), overrides={"camera.fov": value}),
        lambda: lc.Scene.from_dict(value),
        lambda: lc.render(scene, samples=value, progress=False),
        lambda: lc.render(scene, seed=value, progress=False),
        lambda: lc.render(scene, threads=value, progress=False),
        lambda: lc.render(scene, renderer=value, progress=False),
        lambda: lc.render(scene, aovs=value, progress=False),
        lambda: lc.locate(scene, world_point=value),
        lambda: lc.locate(scene, object=value, point=[0, 0, 0]),
        lambda: lc.tonemap(value),
        lambda: lc.tonemap(np.zeros((2, 2, 3), np.float32), exposure=value),
        lambda: next(lc.animate(scene, fps=value, frames=[0], progress=False)),
        lambda: next(lc.animate(scene, frames=[value], progress=False)),
        lambda: lc.read_image(value),
    ]
    for call in calls:
        try:
            result = call()
        except REFUSED as e:
            _check_message(e)
            continue
        except (StopIteration, RuntimeError, OSError) as e:
            _check_message(e)
            continue
        if isinstance(result, np.ndarray) and result.dtype.kind == "f":
            assert np.all(np.isfinite(result))
        elif isinstance(result, tuple) and len(result) == 2 and isinstance(result[1], np.ndarray):
            assert np.all(np.isfinite(result[1]))
