"""lightcone: special-relativistic rendering from Python.

The same library as the ``lightcone`` program, called directly (never the executable): the
same scene files, the same pictures bit for bit, the same error messages.

    import lightcone as lc
    scene = lc.load("scenes/street.json", overrides={"camera.velocity": [0, 0, -0.9]})
    img = lc.render(scene, samples=16)        # numpy float32 (H, W, 3), linear, unclamped
    aov = lc.render(scene, aovs=["doppler", "depth"])   # dict of arrays, "rgb" among them
    png = lc.tonemap(img, exposure=0, curve="filmic")   # uint8 (H, W, 3)
    hit = lc.locate(scene, object="ball", point=[0, 1.4, 0])
    fast = lc.render(scene, renderer="raster")          # the real-time renderer, headless
    lc.physics.doppler_factor(dirs, beta_emitter=[0, 0, 0.5])

See docs/python.md.
"""

from __future__ import annotations

import json as _json
import numbers as _numbers
import os as _os
import sys as _sys
import time as _time
import warnings as _warnings
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

import numpy as _np

from . import _lightcone
from . import physics
from ._lightcone import Scene, SceneError

# The star catalogue (scenes with "stars") travels in the package's data/ folder.
_lightcone.set_data_folder(_os.path.join(_os.path.dirname(__file__), "data"))

__all__ = ["Scene", "SceneError", "Image", "load", "render", "animate", "tonemap", "locate",
           "info", "read_image", "physics"]

_MAX_SAMPLES = 65536  # as the scene format's camera.samples
_MAX_THREADS = 4096  # as the program's --threads
_MAX_FRAME = 10**12 - 1  # as the program's --frames (12 digits)
_TONE_CURVES = ("filmic", "reinhard", "clamp")


class Image(_np.ndarray):
    """A rendered picture: a float32 array (H, W, 3) of linear radiance, the exposure applied.

    It is a numpy array in every way; in a notebook it shows itself (tone-mapped with the
    filmic curve, as the program's PNG)."""

    def _repr_png_(self) -> Optional[bytes]:
        try:
            return _lightcone.png(_np.asarray(self, dtype=_np.float32), 0.0)
        except ValueError:  # NaN has no colour: the notebook shows the array's text instead
            return None


def _shown(value) -> str:
    """A value as a message shows it: its repr, cut to 80 characters and "..." as the program
    cuts a long word (a 10 MB string handed over is not echoed back whole)."""
    text = repr(value)
    return text if len(text) <= 80 else text[:80] + "..."


def _override_lines(overrides: Union[None, Mapping[str, Any], Sequence[str]]) -> list:
    """--set's "key.path=value" lines from a dict (values as JSON, numpy's as numbers and lists;
    NaN, infinity and other types refused with the key named) or from such strings."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        lines = []
        for key, value in overrides.items():
            if not isinstance(key, str):
                raise TypeError(f"overrides: a key must be a JSON path string, got {_shown(key)}")
            lines.append(f"{key}={_lightcone.json_value(value, key)}")
        return lines
    if isinstance(overrides, str) or not all(isinstance(o, str) for o in overrides):
        raise TypeError("overrides: a dict {path: value} or a list of 'path=value' strings")
    return list(overrides)


def _warn(warnings: Iterable[str]) -> None:
    for w in warnings:
        _warnings.warn(w, stacklevel=3)


def _path(function: str, name: str, value) -> str:
    """A file or folder name: a str or an os.PathLike (pathlib.Path), never another type."""
    if not isinstance(value, (str, _os.PathLike)):
        raise TypeError(f"{function}: {name} must be a str or os.PathLike, got "
                        f"{type(value).__name__}")
    path = _os.fsdecode(_os.fspath(value))
    if "\0" in path:  # no file's name holds one; the library's messages would end at it
        raise ValueError(f"{function}: {name} {_shown(path)} holds a NUL character")
    return path


def load(path: Union[str, "_os.PathLike[str]"],
         overrides: Union[None, Mapping[str, Any], Sequence[str]] = None) -> Scene:
    """Reads a scene file (docs/scene-format.md), as ``lightcone render`` reads it.

    path: a str or an os.PathLike (pathlib.Path).
    overrides: values to replace before the scene is checked, as ``--set`` gives them: a dict
    {"camera.velocity": [0, 0, -0.9]} (values as JSON) or a list of "path=value" strings.

    Raises SceneError (with .file, .line and .field) for a scene with an error."""
    scene, warnings = _lightcone.load(_path("load", "path", path), _override_lines(overrides))
    _warn(warnings)
    return scene


def _from_dict(document: Mapping[str, Any], *, folder: Union[None, str, "_os.PathLike[str]"] = None,
               overrides: Union[None, Mapping[str, Any], Sequence[str]] = None) -> Scene:
    """A scene built in code: the scene format (docs/scene-format.md) as dicts, lists, strings,
    numbers (numpy's too; its arrays as lists), booleans and None.

    folder: where relative file names in it (meshes, textures, the sky's image) are read from;
        by default the current folder.
    overrides: as load's.

    Held to a scene file's limits (64 MiB as JSON text, 64 levels of nesting). Raises SceneError
    "<dict>: objects[2].velocity: what is wrong" (.file "<dict>", .line None, .field the path)
    for a scene with an error, NaN and infinity among them."""
    if not isinstance(document, Mapping):
        raise TypeError("Scene.from_dict: a dict in the scene format (docs/scene-format.md), got "
                        f"{type(document).__name__}")
    where = "" if folder is None else _path("Scene.from_dict", "folder", folder)
    scene, warnings = _lightcone.load_dict(document if isinstance(document, dict) else
                                           dict(document), where, _override_lines(overrides))
    _warn(warnings)
    return scene


Scene.from_dict = staticmethod(_from_dict)


class _Progress:
    """The render's progress, once it has run a second: tqdm if installed, else a line on
    stderr."""

    def __init__(self) -> None:
        self.start = _time.monotonic()
        self.bar = None
        self.text = False

    def __call__(self, done: int, total: int) -> None:
        if _time.monotonic() - self.start < 1.0 or total == 0:
            return
        if self.bar is None and not self.text:
            try:
                from tqdm.auto import tqdm  # type: ignore
                self.bar = tqdm(total=total, desc="lightcone", unit="tile")
            except ImportError:
                self.text = True
        if self.bar is not None:
            self.bar.update(done - self.bar.n)
        else:
            _sys.stderr.write(f"\rlightcone: {100 * done // total:3d}% of {total} tiles")
            _sys.stderr.flush()

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.text:
            _sys.stderr.write("\n")


def render(scene: Scene, samples: Optional[int] = None, *, renderer: str = "trace",
           aovs: Optional[Sequence[str]] = None, seed: int = 0, threads: int = 0,
           tessellation: str = "auto", progress: Union[bool, Callable[[int, int], None]] = True):
    """Renders the scene: what ``lightcone render`` writes to its EXR, as numpy arrays.

    samples: per pixel (default: the scene's camera.samples).
    renderer: "trace" (the spectral ray tracer) or "raster" (the real-time renderer, headless
        through EGL: it needs OpenGL 3.3, e.g. Mesa's llvmpipe).
    aovs: output variables of the ray tracer: "doppler", "emission_time", "distance",
        "object", "depth", "normal", "image_order". Then the result is a dict of arrays: "rgb"
        and each variable ((H, W), or (H, W, 3) for "normal").
    seed: of the sample pattern (each seed gives another deterministic picture).
    threads: 0 for all cores.
    progress: True shows a bar (tqdm if installed, else text) once the render has run a
        second; False shows none; a function f(done, total) of tiles is called instead.

    Returns an Image (float32 (H, W, 3), linear radiance times 2^exposure, unclamped), or the
    dict. The render runs without the GIL; Ctrl-C stops it and raises KeyboardInterrupt, whose
    .partial["rgb"] holds the tiles finished (on the main thread; docs/python.md, "Ctrl-C")."""
    if not isinstance(scene, Scene):
        raise TypeError(f"render: scene must be a lightcone.Scene (from load), got {type(scene).__name__}")
    # Their values are the library's rule (renderer_refused, tessellation_refused): a SceneError
    # with the program's message.
    for name, value in (("renderer", renderer), ("tessellation", tessellation)):
        if not isinstance(value, str):
            raise TypeError(f"render: {name} must be a str, got {_shown(value)}")
    if samples is not None:
        if isinstance(samples, bool) or not isinstance(samples, (int, _np.integer)):
            raise TypeError(f"render: samples must be a whole number, got {_shown(samples)}")
        if not 1 <= samples <= _MAX_SAMPLES:
            raise ValueError(f"render: samples must be from 1 to {_MAX_SAMPLES}, got {samples}")
        scene = scene.with_samples(int(samples))
    if isinstance(seed, bool) or not isinstance(seed, (int, _np.integer)) or not 0 <= seed < 2**64:
        raise ValueError(f"render: seed must be a whole number from 0 to {2**64 - 1}, got {_shown(seed)}")
    if (isinstance(threads, bool) or not isinstance(threads, (int, _np.integer))
            or not 0 <= threads <= _MAX_THREADS):
        raise ValueError(f"render: threads must be 0 (all cores) to {_MAX_THREADS}, got "
                         f"{_shown(threads)}")
    if aovs is None:
        aovs = []
    if isinstance(aovs, (str, bytes, Mapping)) or not isinstance(aovs, Iterable):
        raise TypeError(f"render: aovs must be a list of output variables' names, got {_shown(aovs)}")
    names = list(aovs)
    known = _lightcone.aov_names()
    for name in names:
        if not isinstance(name, str) or name not in known:
            raise ValueError(f"render: unknown output variable {_shown(name)} (use {', '.join(known)})")
    shown = _Progress() if progress is True else (progress if callable(progress) else None)
    try:
        result = _lightcone.render(scene, renderer, names, int(seed), int(threads), tessellation,
                                   shown)
    finally:
        if isinstance(shown, _Progress):
            shown.close()
    rgb = result["rgb"].view(Image)
    if not names:
        return rgb
    out = {"rgb": rgb}
    for name in names:
        if name in result:
            out[name] = result[name]
        else:  # "normal.X", "normal.Y", "normal.Z"
            out[name] = _np.stack([result[f"{name}.{axis}"] for axis in "XYZ"], axis=-1)
    return out


def animate(scene: Scene, fps: float = 30, frames: Iterable[int] = range(0, 1), *,
            clock: str = "camera", **render_options):
    """Renders frames of an animation, as ``lightcone animate`` sees them: frame i at the
    camera's proper time tau_0 + i / fps (clock="camera") or at its world time t_0 + i / fps
    (clock="world"), in the scene's units of time. Yields (i, picture) for each i of `frames`;
    render_options are render's (samples, renderer, aovs, seed, threads, progress).

    Each frame is exposed on its own: where the scene's exposure is automatic, the program's
    animation instead averages it over half a second either side of each frame. For frames to
    put in a video, give the scene a fixed exposure (overrides={"render.exposure": EV})."""
    if not isinstance(scene, Scene):
        raise TypeError(f"animate: scene must be a lightcone.Scene, got {type(scene).__name__}")
    fps = _finite("animate", "fps", fps)
    if not fps > 0:
        raise ValueError(f"animate: fps must be a positive number, got {_shown(fps)}")
    if clock not in ("camera", "world"):
        raise ValueError(f"animate: clock must be 'camera' or 'world', got {_shown(clock)}")
    render_options.setdefault("progress", False)
    for i in frames:
        if isinstance(i, bool) or not isinstance(i, (int, _np.integer)):
            raise TypeError(f"animate: a frame number must be a whole number, got {_shown(i)}")
        if not -_MAX_FRAME <= i <= _MAX_FRAME:
            raise ValueError(f"animate: a frame number must be from {-_MAX_FRAME} to {_MAX_FRAME}"
                             f" (12 digits, as the program's --frames), got {i}")
        yield int(i), render(_lightcone.animation_frame(scene, int(i), fps, clock),
                             **render_options)


def _finite(function: str, name: str, value) -> float:
    """A real number (numpy's too) as a finite float, or ValueError naming it."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Real):
        raise TypeError(f"{function}: {name} must be a number, got {_shown(value)}")
    try:
        number = float(value)
    except OverflowError:
        number = float("inf")
    if not _np.isfinite(number):
        raise ValueError(f"{function}: {name} must be a finite number, got {_shown(value)}")
    return number


def tonemap(image, exposure: float = 0.0, curve: str = "filmic") -> _np.ndarray:
    """The 8-bit picture of a linear image, as the program's PNG: times 2^exposure, through the
    tone curve ("filmic", "reinhard" or "clamp"), sRGB-encoded. Returns uint8 (H, W, 3).

    An image holding NaN is refused (ValueError, with the count): NaN has no colour."""
    if curve not in _TONE_CURVES:
        raise ValueError(f"tonemap: curve must be one of {', '.join(_TONE_CURVES)}, got {_shown(curve)}")
    exposure = _finite("tonemap", "exposure", exposure)
    try:
        array = _np.asarray(image, dtype=_np.float32)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"tonemap: the image must be an array of numbers of shape (H, W, 3), "
                         f"got {_shown(image)}") from None
    if array.ndim != 3 or array.shape[2] != 3:
        raise ValueError(f"tonemap: the image must have shape (H, W, 3), got {array.shape}")
    return _lightcone.tonemap(array, exposure, curve)


def _number_list(name: str, value) -> list:
    """A sequence of numbers, as given: how many a request takes is the library's rule."""
    try:
        array = _np.asarray(value, dtype=_np.float64)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"locate: {name} must be numbers, got {_shown(value)}") from None
    if array.ndim != 1:
        raise ValueError(f"locate: {name} must be a sequence of numbers, got shape {array.shape}")
    return array.tolist()


def _triple(name: str, value) -> list:
    try:
        array = _np.asarray(value, dtype=_np.float64)
    except OverflowError:
        raise ValueError(f"locate: {name} must be finite") from None
    except (TypeError, ValueError):
        raise ValueError(f"locate: {name} must be three numbers, got {_shown(value)}") from None
    if array.shape != (3,):
        raise ValueError(f"locate: {name} must be three numbers, got shape {array.shape}")
    if not _np.all(_np.isfinite(array)):
        raise ValueError(f"locate: {name} must be finite")
    return array.tolist()


def locate(scene: Scene, object: Optional[str] = None, point=None, world_point=None,
           direction=None, pixel=None) -> dict:
    """Where a point or direction appears in the picture: the fields of ``lightcone locate``'s
    JSON (pixel, direction, emission event, distance, in_view, doppler; near a black hole every
    image). Give exactly one of point (in the object's own coordinates, with object),
    world_point (at rest in the scene's frame) or direction (of the sky); or pixel=(x, y), a
    point of the picture (pixel (i, j) covers [i, i+1) x [j, j+1)), for what is seen there: the
    fields of ``lightcone locate --pixel`` (meets, object and point, sky or disk, the emission
    event, doppler; near a black hole the image order)."""
    given = [v is not None for v in (point, world_point, direction, pixel)]
    if sum(given) != 1:
        raise ValueError("locate: give exactly one of point (with object), world_point, "
                         "direction, pixel")
    if pixel is not None:
        return _json.loads(_lightcone.probe(scene, _number_list("pixel", pixel), object is not None))
    if point is not None:
        if not isinstance(object, str):
            raise ValueError("locate: point needs object=NAME")
        return _json.loads(_lightcone.locate(scene, "point", object, _triple("point", point)))
    if world_point is not None:
        return _json.loads(_lightcone.locate(scene, "world_point", "",
                                             _triple("world_point", world_point)))
    d = _triple("direction", direction)
    if not any(d):
        raise ValueError("locate: direction must not be zero")
    return _json.loads(_lightcone.locate(scene, "direction", "", d))


def info(scene: Scene) -> dict:
    """What ``lightcone info --json`` tells of the scene: the image, each body's speed and
    gamma, the Doppler range, when the light seen left the scene, triangles, memory; near a
    black hole its horizon, photon sphere, ISCO and shadow; the stars."""
    if not isinstance(scene, Scene):
        raise TypeError(f"info: scene must be a lightcone.Scene, got {type(scene).__name__}")
    return _json.loads(_lightcone.info(scene))


def read_image(path: str) -> dict:
    """An image file as the program reads it (PNG, JPEG: linear from sRGB; OpenEXR: as stored,
    with its output variables): a dict with "rgb" (float32 (H, W, 3)), each other channel, and
    "exposure": the EV the renderer applied to an EXR it wrote (its radiance is rgb / 2**EV), or
    None where the file does not say."""
    return _lightcone.read_image(_path("read_image", "path", path))
