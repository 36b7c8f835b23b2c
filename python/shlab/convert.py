"""Conversions of coefficient vectors between normalisations (sh_convert)
and between the cs and nocs conventions (sh_convention_switch).

Normalisations (docs/CONVENTIONS.md): "cs" orthonormal with the
Condon-Shortley phase (the default), "nocs" orthonormal without it, "4pi"
4π-normalised without phase (SHTOOLS' default), "schmidt" Schmidt
semi-normalised without phase.  The represented function is kept:
coefficients transform inversely to the basis functions.

Coefficients are arrays of shape (..., n²): every vector along the last
axis is converted (its order n from the length).
"""
import ctypes

import numpy as np

from . import _names
from ._lib import declare, lib, order_of, real_array

__all__ = ["convert", "convert_inplace", "convention_switch", "convention_switch_inplace"]

_sh_convert = declare("sh_convert", [ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_void_p])
_sh_switch = declare("sh_convention_switch", [ctypes.c_int, ctypes.c_void_p], None, status=False)


def convert_inplace(coeffs, src, dst):
    """Convert ``coeffs`` (C-contiguous float64, shape (..., n²)) from
    normalisation ``src`` to ``dst`` in place; returns it.  Any other array
    is refused (TypeError) rather than silently copied."""
    c = real_array(coeffs, np.float64, "coeffs", writable=True, copy_ok=False)
    if c.ndim < 1:
        raise ValueError("coeffs must have at least one axis")
    order = order_of(c.shape[-1])
    a, b = _names.norm(src), _names.norm(dst)
    flat = c.reshape(-1, c.shape[-1])
    step = c.shape[-1] * 8
    if flat.shape[0] == 0:
        return c
    for k in range(flat.shape[0]):
        _sh_convert(order, a, b, c.ctypes.data + k * step)
    return c


def convert(coeffs, src, dst):
    """A converted copy of ``coeffs`` (any real array of shape (..., n²));
    see convert_inplace."""
    return convert_inplace(np.array(real_array(coeffs, np.float64, "coeffs"), dtype=np.float64, order="C"),
                           src, dst)


def convention_switch_inplace(coeffs):
    """Switch ``coeffs`` (C-contiguous float64, shape (..., n²)) between cs
    and nocs in place (odd m negated); returns it."""
    c = real_array(coeffs, np.float64, "coeffs", writable=True, copy_ok=False)
    if c.ndim < 1:
        raise ValueError("coeffs must have at least one axis")
    order = order_of(c.shape[-1])
    flat = c.reshape(-1, c.shape[-1])
    for k in range(flat.shape[0]):
        _sh_switch(order, c.ctypes.data + k * c.shape[-1] * 8)
    return c


def convention_switch(coeffs):
    """A copy of ``coeffs`` switched between cs and nocs (the switch is its own inverse)."""
    return convention_switch_inplace(np.array(real_array(coeffs, np.float64, "coeffs"), dtype=np.float64,
                                              order="C"))
