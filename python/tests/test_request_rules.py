"""The Python door to the library's rules (src/lightcone/frame/request_rules.hpp): each case of
tests/data/refused-requests.json is refused with the message the program prints for it
(tests/test_request_rules.cpp), and nothing is rendered or located.

Run by ctest (Python.pytest) with LIGHTCONE_BINARY the program and LIGHTCONE_SOURCE_DIR the
repository."""

import json
import os
import subprocess

import numpy as np
import pytest

import lightcone as lc

BINARY = os.environ.get("LIGHTCONE_BINARY", "build/lightcone")
SOURCE = os.environ.get("LIGHTCONE_SOURCE_DIR", ".")

with open(os.path.join(SOURCE, "tests", "data", "refused-requests.json")) as f:
    CASES = json.load(f)["cases"]


def _written(case, folder):
    path = folder / f"{case['name']}.json"
    path.write_text(json.dumps(case["scene"], indent=1))
    return str(path)


def _programs_message(case, path, folder):
    if "locate" in case:
        args = ["locate", path, "--world-point", ",".join(str(v) for v in case["locate"]["world_point"])]
    else:
        args = ["render", path, "-o", str(folder / "out.exr")]
        for name in case.get("render", {}).get("aovs", []):
            args += ["--aov", name]
        args += ["--renderer", case.get("render", {}).get("renderer", "trace")]
    done = subprocess.run([BINARY, *args], capture_output=True, text=True)
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith("lightcone: ")
    return done.stderr[len("lightcone: "):].rstrip("\n")


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_each_refusal_is_the_programs(tmp_path, case):
    path = _written(case, tmp_path)
    expected = f"{path}: {case['refusal']}"
    assert _programs_message(case, path, tmp_path) == expected
    scene = lc.load(path)
    with pytest.raises(lc.SceneError) as refused:
        if "locate" in case:
            lc.locate(scene, world_point=case["locate"]["world_point"])
        else:
            request = case.get("render", {})
            lc.render(scene, renderer=request.get("renderer", "trace"), aovs=request.get("aovs"),
                      progress=False)
    assert str(refused.value) == expected


@pytest.mark.parametrize("option,request_", [
    ("--renderer", {"renderer": "bogus"}),
    ("--tessellation", {"renderer": "raster", "tessellation": "nope"}),
])
def test_renderer_and_tessellation_names_are_refused_as_the_program_refuses_them(
        tmp_path, option, request_):
    path = os.path.join(SOURCE, "scenes", "terrell.json")
    args = [a for key, value in request_.items() for a in (f"--{key}", value)]
    done = subprocess.run([BINARY, "render", path, "-o", str(tmp_path / "out.png"), *args],
                          capture_output=True, text=True)
    assert done.returncode == 2
    with pytest.raises(lc.SceneError) as refused:
        lc.render(lc.load(path), progress=False, **request_)
    assert done.stderr == f"lightcone: {option}: {refused.value} (see --help)\n"


@pytest.mark.parametrize("renderer", ["trace", "raster"])
def test_the_raster_renderer_refuses_alike(tmp_path, renderer):
    case = next(c for c in CASES if c["name"] == "classical-hole")
    path = _written(case, tmp_path)
    with pytest.raises(lc.SceneError, match="curved spacetime has no classical picture"):
        lc.render(lc.load(path), renderer=renderer, progress=False)


@pytest.mark.parametrize("samples", [0, -1, 65537])
def test_a_scene_changed_in_code_keeps_the_cameras_limits(samples):
    # 0 samples gave an all-NaN picture, -1 an all-black one.
    scene = lc.load(os.path.join(SOURCE, "scenes", "terrell.json"))
    with pytest.raises(lc.SceneError,
                       match=f"terrell.json: camera.samples: must be an integer from 1 to 65536, got {samples}"):
        scene.with_samples(samples)


@pytest.mark.parametrize("scene,setting", [
    ("black-hole.json", "black_hole.disk.luminance=1e308"),  # gave NaNs
    ("stars.json", "sky.stars.exposure=1000"),  # gave infinities
])
@pytest.mark.parametrize("renderer", ["trace", "raster"])
def test_radiance_beyond_a_float_is_refused_as_the_program_refuses_it(tmp_path, scene, setting,
                                                                       renderer):
    path = os.path.join(SOURCE, "scenes", scene)
    small = ["--set", "camera.width=48", "--set", "camera.height=27", "--set", "camera.samples=1"]
    done = subprocess.run([BINARY, "render", path, "-o", str(tmp_path / "out.png"), "--set",
                           setting, "--renderer", renderer, *small], capture_output=True, text=True)
    assert done.returncode == 1
    message = done.stderr.removeprefix("lightcone: error: ").rstrip("\n")
    assert message.startswith(f"{path}: the render has ") and "non-finite value" in message
    key, value = setting.split("=")
    overrides = {key: float(value), "camera.width": 48, "camera.height": 27, "camera.samples": 1}
    with pytest.raises(RuntimeError) as refused:
        lc.render(lc.load(path, overrides=overrides), renderer=renderer, progress=False)
    assert str(refused.value) == message
    assert not (tmp_path / "out.png").exists()


def test_no_non_finite_picture_is_returned(tmp_path):
    path = tmp_path / "bright.json"
    path.write_text(json.dumps({
        "camera": {"position": [0, 0, 0], "width": 8, "height": 6},
        "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [0, 0, -5],
                     "material": {"color": [1, 1, 1]}}],
        "render": {"exposure": 1000}}))
    done = subprocess.run([BINARY, "render", str(path), "-o", str(tmp_path / "out.png")],
                          capture_output=True, text=True)
    assert done.returncode != 0
    message = done.stderr.removeprefix("lightcone: error: ").rstrip("\n")
    assert "non-finite values" in message
    with pytest.raises(RuntimeError) as refused:
        lc.render(lc.load(str(path)), progress=False)
    assert str(refused.value) == message
    assert not (tmp_path / "out.png").exists()

