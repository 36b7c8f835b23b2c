"""Evaluation of the real SH basis (sh_eval, sh_eval_dir).

Conventions (docs/CONVENTIONS.md): direction s = (sinθ cosφ, sinθ sinφ, cosθ),
z up; coefficient i = l(l+1)+m belongs to band l, order m; "order n" means the
n² functions of bands 0..n-1; convention "cs" (Condon-Shortley phase, the
default) or "nocs" (odd m negated).

The C routines evaluate one point per call; these functions loop over the
points in Python and write each point's n² values straight into the output
array (no temporary per point).  Expect ~1 µs of overhead per point.
"""
import ctypes

import numpy as np

from . import _names
from ._lib import check_order, declare, out_array, real_array

__all__ = ["eval_angles", "eval_dir", "dir_from_angles", "angles_from_dir"]

_P = ctypes.c_void_p
_sh_eval = declare("sh_eval", [ctypes.c_int, ctypes.c_int, ctypes.c_double, ctypes.c_double, _P])
_sh_eval_dir = declare("sh_eval_dir", [ctypes.c_int, ctypes.c_int, _P, _P])
_sh_angles_from_dir = declare("sh_angles_from_dir", [_P, _P, _P])


def eval_angles(order, theta, phi, convention="cs", out=None):
    """All order² real SH at the directions (theta, phi) (radians).

    theta and phi broadcast against each other (scalars or arrays of any
    shape S); the result has shape S + (order²,), float64.  ``out`` (optional)
    must be a C-contiguous float64 array of exactly that shape.  Raises
    shlab.Error for an order outside 1..4097 or a bad convention name."""
    order = check_order(order)
    conv = _names.convention(convention)
    th, ph = np.broadcast_arrays(real_array(theta, np.float64, "theta"), real_array(phi, np.float64, "phi"))
    shape = th.shape
    n2 = order * order
    res = out_array(out, shape + (n2,), np.float64)
    th = th.reshape(-1)
    ph = ph.reshape(-1)
    base, step = res.ctypes.data, n2 * 8
    for k in range(th.size):
        _sh_eval(order, conv, float(th[k]), float(ph[k]), base + k * step)
    return res


def eval_dir(order, dirs, convention="cs", out=None):
    """All order² real SH at directions given as vectors.

    ``dirs`` has shape S + (3,) (any finite non-zero vectors; each is
    normalised); the result has shape S + (order²,).  A zero, NaN or infinite
    vector raises shlab.Error (SH_EINVAL) with shlab's message.  ``dirs`` is
    converted with np.ascontiguousarray (float64) if it is not already so."""
    order = check_order(order)
    conv = _names.convention(convention)
    d = real_array(dirs, np.float64, "dirs")
    if d.ndim < 1 or d.shape[-1] != 3:
        raise ValueError("dirs must have shape (..., 3), not %s" % (d.shape,))
    shape = d.shape[:-1]
    n2 = order * order
    res = out_array(out, shape + (n2,), np.float64)
    d2 = d.reshape(-1, 3)
    base, step, dbase = res.ctypes.data, n2 * 8, d2.ctypes.data
    for k in range(d2.shape[0]):
        _sh_eval_dir(order, conv, dbase + 24 * k, base + k * step)
    return res


def dir_from_angles(theta, phi):
    """Unit vectors (sinθ cosφ, sinθ sinφ, cosθ), shape broadcast(theta, phi) + (3,)."""
    th, ph = np.broadcast_arrays(np.asarray(theta, dtype=np.float64), np.asarray(phi, dtype=np.float64))
    return np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], axis=-1)


def angles_from_dir(dirs):
    """(theta, phi) of vectors of shape S + (3,), θ in [0, π], φ in [0, 2π)
    (sh_angles_from_dir; a zero or non-finite vector raises shlab.Error)."""
    d = real_array(dirs, np.float64, "dirs")
    if d.ndim < 1 or d.shape[-1] != 3:
        raise ValueError("dirs must have shape (..., 3), not %s" % (d.shape,))
    d2 = d.reshape(-1, 3)
    th = np.empty(d2.shape[0])
    ph = np.empty(d2.shape[0])
    for k in range(d2.shape[0]):
        _sh_angles_from_dir(d2.ctypes.data + 24 * k, th.ctypes.data + 8 * k, ph.ctypes.data + 8 * k)
    return th.reshape(d.shape[:-1]), ph.reshape(d.shape[:-1])
