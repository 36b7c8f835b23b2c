"""Rotations of the sphere (sh_rotation and its constructors).

A rotation R (3×3, proper orthogonal) acts on functions, g(s) = f(R⁻¹ s);
Euler angles are ZYZ active, R = Rz(α) Ry(β) Rz(γ); quaternions are (w, x,
y, z), active (docs/CONVENTIONS.md).  A :class:`Rotation` holds both the
matrix and ZYZ angles that reproduce it, as shlab's sh_rotation does.
"""
import ctypes

import numpy as np

from ._lib import declare, finite, real_array

__all__ = ["Rotation", "as_rotation"]


class CRotation(ctypes.Structure):
    """ctypes mirror of sh_rotation (src/shlab/rotate.h)."""
    _fields_ = [("R", ctypes.c_double * 9), ("alpha", ctypes.c_double), ("beta", ctypes.c_double),
                ("gamma", ctypes.c_double)]


_RP = ctypes.POINTER(CRotation)
_P = ctypes.c_void_p
_from_euler = declare("sh_rotation_from_euler", [ctypes.c_double] * 3 + [_RP])
_from_quat = declare("sh_rotation_from_quat", [_P, ctypes.c_int, _RP])
_from_axis_angle = declare("sh_rotation_from_axis_angle", [_P, ctypes.c_double, _RP])
_from_matrix = declare("sh_rotation_from_matrix", [_P, ctypes.c_int, _RP])
_inverse = declare("sh_rotation_inverse", [_RP, _RP], None, status=False)
_compose = declare("sh_rotation_compose", [_RP, _RP, _RP], None, status=False)
_to_quat = declare("sh_rotation_to_quat", [_RP, _P], None, status=False)
_to_axis_angle = declare("sh_rotation_to_axis_angle", [_RP, _P, ctypes.POINTER(ctypes.c_double)], None,
                         status=False)


def _vec(v, n, what):
    a = real_array(v, np.float64, what)
    if a.shape != (n,):
        raise ValueError("%s must have shape (%d,), not %s" % (what, n, a.shape))
    return a


class Rotation:
    """A rotation: ``matrix`` (3×3 ndarray), ``euler`` (α, β, γ ZYZ radians),
    ``quat`` (w, x, y, z with w ≥ 0), ``axis_angle``.  Made by the class
    methods (each one shlab's constructor, which checks its input and raises
    shlab.Error with shlab's message).  ``A @ B`` composes (the matrix
    product AB), ``inverse()`` gives Rᵀ."""

    __slots__ = ("_c",)

    def __init__(self, c):
        if not isinstance(c, CRotation):
            raise TypeError("use Rotation.from_euler / from_quat / from_matrix / from_axis_angle")
        self._c = c

    @classmethod
    def from_euler(cls, alpha, beta, gamma):
        """R = Rz(α) Ry(β) Rz(γ), radians (sh_rotation_from_euler)."""
        c = CRotation()
        _from_euler(finite(alpha, "alpha"), finite(beta, "beta"), finite(gamma, "gamma"), ctypes.byref(c))
        return cls(c)

    @classmethod
    def from_quat(cls, q, orthonormalize=False):
        """A unit quaternion (w, x, y, z), active.  |q| must be within 1e-6
        of 1 unless orthonormalize (then any non-zero q is normalised)."""
        q = _vec(q, 4, "quaternion")
        c = CRotation()
        _from_quat(q.ctypes.data, 1 if orthonormalize else 0, ctypes.byref(c))
        return cls(c)

    @classmethod
    def from_matrix(cls, m, orthonormalize=False):
        """A 3×3 matrix (array of shape (3, 3) or (9,) row-major).  Refused
        unless max|RᵀR − I| ≤ 1e-6 and det R > 0, unless orthonormalize
        (the nearest proper rotation is then used)."""
        m = real_array(m, np.float64, "matrix")
        if m.shape not in ((3, 3), (9,)):
            raise ValueError("matrix must have shape (3, 3) or (9,), not %s" % (m.shape,))
        c = CRotation()
        _from_matrix(m.ctypes.data, 1 if orthonormalize else 0, ctypes.byref(c))
        return cls(c)

    @classmethod
    def from_axis_angle(cls, axis, angle):
        """Rotation by ``angle`` (radians, right-hand rule) about ``axis`` (non-zero)."""
        a = _vec(axis, 3, "axis")
        c = CRotation()
        _from_axis_angle(a.ctypes.data, finite(angle, "angle"), ctypes.byref(c))
        return cls(c)

    @property
    def matrix(self):
        """The 3×3 matrix (a copy)."""
        return np.array(self._c.R[:], dtype=np.float64).reshape(3, 3)

    @property
    def euler(self):
        """(α, β, γ): α, γ ∈ (−π, π], β ∈ [0, π]."""
        return (self._c.alpha, self._c.beta, self._c.gamma)

    @property
    def quat(self):
        """Unit quaternion (w, x, y, z), w ≥ 0."""
        q = np.empty(4)
        _to_quat(ctypes.byref(self._c), q.ctypes.data)
        return q

    @property
    def axis_angle(self):
        """(axis (3,), angle ∈ [0, π])."""
        a = np.empty(3)
        t = ctypes.c_double()
        _to_axis_angle(ctypes.byref(self._c), a.ctypes.data, ctypes.byref(t))
        return a, t.value

    def inverse(self):
        """The inverse rotation Rᵀ (sh_rotation_inverse)."""
        c = CRotation()
        _inverse(ctypes.byref(self._c), ctypes.byref(c))
        return Rotation(c)

    def __matmul__(self, other):
        if not isinstance(other, Rotation):
            return NotImplemented
        c = CRotation()
        _compose(ctypes.byref(self._c), ctypes.byref(other._c), ctypes.byref(c))
        return Rotation(c)

    def __repr__(self):
        return "Rotation.from_euler(%r, %r, %r)" % self.euler

    @property
    def c(self):
        """The ctypes sh_rotation (for passing to C)."""
        return self._c


def as_rotation(rot):
    """A Rotation from a Rotation, a (3, 3) matrix, a (4,) quaternion
    (w, x, y, z) or a (3,) triple of ZYZ Euler angles (radians)."""
    if isinstance(rot, Rotation):
        return rot
    a = real_array(rot, np.float64, "rotation")
    if a.shape == (3, 3):
        return Rotation.from_matrix(a)
    if a.shape == (4,):
        return Rotation.from_quat(a)
    if a.shape == (3,):
        return Rotation.from_euler(*a)
    raise ValueError("a rotation is a Rotation, a (3, 3) matrix, a (4,) quaternion (w, x, y, z) or (3,) ZYZ "
                     "Euler angles; got shape %s" % (a.shape,))
