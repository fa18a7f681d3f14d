"""lightcone's physics kernels over numpy arrays.

Each function broadcasts its arguments (numpy's rules) and calls the library's scalar kernel
on every element, so that it gives the C++ kernel's numbers bit for bit. Directions and
velocities are 3-vectors in the last axis; velocities are in units of c (|beta| < 1); events
are (t, x, y, z).
"""

from __future__ import annotations

import numpy as _np

from . import _lightcone

__all__ = ["aberrate", "doppler_factor", "lorentz_boost", "retarded_time", "blackbody",
           "received_blackbody", "received_spectrum"]

_kernels = _lightcone.physics


def _vectors(name: str, value, width: int) -> _np.ndarray:
    array = _np.asarray(value, dtype=_np.float64)
    if array.ndim == 0 or array.shape[-1] != width:
        raise ValueError(f"{name}: the last axis must hold {width} numbers, got shape {array.shape}")
    return array


def _speeds(name: str, beta: _np.ndarray) -> None:
    if not _np.all(_np.isfinite(beta)):
        raise ValueError(f"{name}: must be finite")
    if _np.any(_np.einsum("...i,...i->...", beta, beta) >= 1):
        raise ValueError(f"{name}: every speed must be below c (|beta| < 1)")


def _rows(*arrays):
    """The arrays broadcast to one shape, each as rows of its last axis, and that shape. An
    array of one vector stays one row (the kernels read it for every element: no copy)."""
    shape = _np.broadcast_shapes(*(a.shape[:-1] for a in arrays))
    rows = []
    for a in arrays:
        if a.size == a.shape[-1]:
            rows.append(_np.ascontiguousarray(a.reshape(1, a.shape[-1])))
        else:
            rows.append(_np.ascontiguousarray(
                _np.broadcast_to(a, shape + a.shape[-1:]).reshape(-1, a.shape[-1])))
    return rows, shape


def aberrate(directions, beta):
    """Look directions (unit, from the observer toward the source) as seen in a frame moving
    with velocity beta relative to the frame they are given in. Exact (docs/physics.md)."""
    d = _vectors("directions", directions, 3)
    b = _vectors("beta", beta, 3)
    _speeds("beta", b)
    (dr, br), shape = _rows(d, b)
    return _kernels.aberrate(dr, br).reshape(shape + (3,))


def doppler_factor(n, beta_emitter, beta_receiver=(0.0, 0.0, 0.0)):
    """D = nu_received / nu_emitted for light travelling along the unit direction n (from the
    emitter toward the receiver), the emitter and the receiver moving with beta_emitter and
    beta_receiver in one frame: the ratio of k.U of the photon's 4-momentum with their
    4-velocities. D > 1 is a blueshift."""
    nn = _vectors("n", n, 3)
    e = _vectors("beta_emitter", beta_emitter, 3)
    r = _vectors("beta_receiver", beta_receiver, 3)
    _speeds("beta_emitter", e)
    _speeds("beta_receiver", r)
    (nr, er, rr), shape = _rows(nn, e, r)
    return _kernels.doppler_factor(nr, er, rr).reshape(shape)


def lorentz_boost(events, beta):
    """Events (t, x, y, z) in the coordinates of a frame moving with velocity beta (the pure
    boost, c = 1)."""
    x = _vectors("events", events, 4)
    b = _vectors("beta", beta, 3)
    _speeds("beta", b)
    (xr, br), shape = _rows(x, b)
    return _kernels.lorentz_boost(xr, br).reshape(shape + (4,))


def retarded_time(observer_events, position, velocity, time=0.0, phases=None):
    """The time at which light seen at observer_events (t, x, y, z) left a body.

    Inertial (phases None): X(t) = position + velocity (t - time), the root on the past light
    cone in closed form (exact in both directions of motion); every argument broadcasts.

    Accelerated: the scene format's world-line through (time, position) with `velocity` at
    proper time 0, then each phase (duration, [ax, ay, az]) in turn: a constant proper
    acceleration for that proper duration (a hyperbola), inertial before the first and after
    the last. One world-line for all the events; the root is in closed form on each piece."""
    obs = _vectors("observer_events", observer_events, 4)
    p = _vectors("position", position, 3)
    v = _vectors("velocity", velocity, 3)
    _speeds("velocity", v)
    if phases is not None:
        if p.shape != (3,) or v.shape != (3,) or _np.ndim(time) != 0:
            raise ValueError("retarded_time: with phases, one position, velocity and time")
        pieces = []
        for phase in phases:
            duration, acceleration = phase
            a = _vectors("phases' acceleration", acceleration, 3)
            if not (float(duration) >= 0 and _np.all(_np.isfinite(a)) and a.shape == (3,)):
                raise ValueError("retarded_time: each phase is (duration >= 0, [ax, ay, az]), finite")
            pieces.append((float(duration), a.tolist()))
        rows = _np.ascontiguousarray(obs.reshape(-1, 4))
        return _kernels.retarded_time_accelerated(rows, float(time), p.tolist(), v.tolist(),
                                                  pieces).reshape(obs.shape[:-1])
    t0 = _np.asarray(time, dtype=_np.float64)[..., None]
    (obs_r, p_r, v_r, t_r), shape = _rows(obs, p, v, t0)
    n = max(len(obs_r), len(p_r), len(v_r), len(t_r))
    obs_r, p_r, v_r, t_r = (_np.broadcast_to(a, (n, a.shape[1])) for a in (obs_r, p_r, v_r, t_r))
    t_receive = obs_r[:, 0]
    delta = p_r + v_r * (t_receive - t_r[:, 0])[:, None] - obs_r[:, 1:]
    return (t_receive - _kernels.retarded_delay(_np.ascontiguousarray(delta),
                                                 _np.ascontiguousarray(v_r))).reshape(shape)


def _scalars(name: str, value) -> _np.ndarray:
    array = _np.asarray(value, dtype=_np.float64)
    if not _np.all(_np.isfinite(array)):
        raise ValueError(f"{name}: must be finite")
    return array[..., None]


def _searchlight(function: str, name: str) -> None:
    if name not in ("physical", "chang1996", "off"):
        raise ValueError(f"{function}: searchlight must be physical, chang1996 or off, got {name!r}")


def blackbody(wavelength_nm, temperature_k):
    """Planck's law: the spectral radiance of a blackbody (W sr^-1 m^-2 nm^-1) at each
    wavelength (nm) and temperature (K)."""
    lam = _scalars("wavelength_nm", wavelength_nm)
    t = _scalars("temperature_k", temperature_k)
    if _np.any(lam <= 0) or _np.any(t <= 0):
        raise ValueError("blackbody: wavelengths and temperatures must be positive")
    (lr, tr), shape = _rows(lam, t)
    return _kernels.blackbody(lr, tr).reshape(shape)


def received_blackbody(temperature_k, doppler, luminance=None, searchlight="physical"):
    """The linear sRGB colour received from a blackbody of temperature T seen with Doppler
    factor D: the CIE 1931 observer's integral of the received spectral radiance, the
    searchlight factor (D^5 "physical", D "chang1996", 1 "off") times L(D lambda). `luminance`:
    the blackbody scaled to that CIE Y at rest (the scene format's "luminance"); None: Planck's
    radiance itself. Returns (..., 3)."""
    t = _scalars("temperature_k", temperature_k)
    d = _scalars("doppler", doppler)
    if _np.any(t <= 0) or _np.any(d <= 0):
        raise ValueError("received_blackbody: temperatures and Doppler factors must be positive")
    _searchlight("received_blackbody", searchlight)
    if luminance is None:
        y = -_np.ones_like(t)  # (the kernel's mark for Planck's radiance itself)
    else:
        y = _scalars("luminance", luminance)
        if _np.any(y < 0):
            raise ValueError("received_blackbody: luminance must be 0 or more")
    (tr, dr, yr), shape = _rows(t, d, y)
    return _kernels.received_blackbody(tr, dr, yr, searchlight).reshape(shape + (3,))


def received_spectrum(wavelengths_nm, values, doppler, searchlight="physical"):
    """The linear sRGB colour received from an emitter whose spectral radiance at rest is the
    table (wavelengths_nm, values) (piecewise linear, the end values held outside it: the
    scene format's "spectrum"), seen with each Doppler factor: the CIE 1931 observer's integral
    of the searchlight factor times L(D lambda). Returns doppler's shape + (3,)."""
    lam = _np.asarray(wavelengths_nm, dtype=_np.float64)
    val = _np.asarray(values, dtype=_np.float64)
    if lam.ndim != 1 or lam.shape != val.shape or lam.size < 2:
        raise ValueError("received_spectrum: wavelengths_nm and values: two 1-D arrays of one "
                         "length, at least 2")
    if not (_np.all(_np.isfinite(lam)) and _np.all(_np.isfinite(val)) and _np.all(lam > 0)
            and _np.all(_np.diff(lam) > 0)):
        raise ValueError("received_spectrum: wavelengths must be positive and increasing, "
                         "values finite")
    d = _scalars("doppler", doppler)
    if _np.any(d <= 0):
        raise ValueError("received_spectrum: Doppler factors must be positive")
    _searchlight("received_spectrum", searchlight)
    rows = _np.ascontiguousarray(d.reshape(-1, 1))
    return _kernels.received_spectrum(lam.tolist(), val.tolist(), rows,
                                      searchlight).reshape(d.shape[:-1] + (3,))
