"""Rotation of SH coefficient vectors: the rotator (sh_rotator_*), its
per-thread plans with batches (sh_rot_plan_*), the high-band stream
(sh_rot_stream_*) and single bands (sh_rot_band_apply).

Coefficient vectors are float64 (or float32 for float rotators and plans)
arrays whose last axis holds the order² coefficients.  Arrays that already
have the dtype the C side wants and are C-contiguous are passed without a
copy; anything else is converted with np.ascontiguousarray (a copy).

A rotation may be given as a :class:`shlab.Rotation`, a (3, 3) matrix, a (4,)
quaternion (w, x, y, z) or (3,) ZYZ Euler angles (radians); see
docs/CONVENTIONS.md for the direction of a rotation (R_sh(AB) = R_sh(A) R_sh(B)).
"""
import ctypes

import numpy as np

from . import _names
from ._lib import Error, check_order, declare, out_array, real_array
from .rotation import CRotation, Rotation, as_rotation

__all__ = ["Rotator", "Plan", "Stream", "rotate_band", "rotation_matrix", "method_max_order",
           "kernel_available"]

_P = ctypes.c_void_p
_RP = ctypes.POINTER(CRotation)
_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_char_p)


class _Opts(ctypes.Structure):
    """ctypes mirror of sh_rotator_opts (src/shlab/rotate.h)."""
    _fields_ = [("order", ctypes.c_int), ("method", ctypes.c_int), ("prec", ctypes.c_int),
                ("kernel", ctypes.c_int), ("conv", ctypes.c_int), ("threads", ctypes.c_int),
                ("progress", _PROGRESS), ("progress_ctx", ctypes.c_void_p)]


_create = declare("sh_rotator_create", [ctypes.POINTER(_Opts), ctypes.POINTER(_P)])
_free = declare("sh_rotator_free", [_P], None, status=False)
_r_int = {k: declare("sh_rotator_" + k, [_P], ctypes.c_int, status=False)
          for k in ("order", "method", "precision", "kernel", "threads", "streams")}
_r_bytes = declare("sh_rotator_bytes", [_P, ctypes.POINTER(ctypes.c_size_t)], ctypes.c_size_t, status=False)
_apply = declare("sh_rotator_apply", [_P, _RP, ctypes.c_uint, ctypes.c_int, _P, _P])
_apply_matrix = declare("sh_rotator_apply_matrix", [_P, _P, ctypes.c_uint, ctypes.c_int, _P, _P])
_apply_matrix_f = declare("sh_rotator_apply_matrix_f", [_P, _P, _P, _P])
_plan = declare("sh_rotator_plan", [_P, ctypes.POINTER(_P)])
_plan_free = declare("sh_rot_plan_free", [_P], None, status=False)
_plan_set = declare("sh_rot_plan_set", [_P, _RP])
_plan_set_matrix = declare("sh_rot_plan_set_matrix", [_P, _P])
_plan_set_quat = declare("sh_rot_plan_set_quat", [_P, _P])
_plan_set_matrix_f = declare("sh_rot_plan_set_matrix_f", [_P, _P])
_plan_set_quat_f = declare("sh_rot_plan_set_quat_f", [_P, _P])
_plan_apply = declare("sh_rot_plan_apply", [_P, _P, _P])
_plan_apply_f = declare("sh_rot_plan_apply_f", [_P, _P, _P])
_plan_blocks = declare("sh_rot_plan_blocks", [_P, _P])
_plan_kernel = declare("sh_rot_plan_kernel", [_P], ctypes.c_int, status=False)
_many = {name: declare("sh_rot_plan_" + name, [_P, ctypes.c_size_t, _P, _P] if "apply" in name
                       else [_P, ctypes.c_size_t, _P, _P, _P])
         for name in ("apply_many", "apply_many_f", "rotate_many", "rotate_many_f", "rotate_many_quat",
                      "rotate_many_quat_f")}
_blocks_to_dense = declare("sh_rot_blocks_to_dense", [ctypes.c_int, _P, _P], None, status=False)
_stream_create = declare("sh_rot_stream_create", [ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.POINTER(_P)])
_stream_free = declare("sh_rot_stream_free", [_P], None, status=False)
_stream_threads = declare("sh_rot_stream_threads", [_P], ctypes.c_int, status=False)
_stream_apply = declare("sh_rot_stream_apply", [_P, ctypes.c_int, _RP, ctypes.c_int, ctypes.c_int, _P, _P])
_band_apply = declare("sh_rot_band_apply", [ctypes.c_int, ctypes.c_int, _RP, ctypes.c_int, ctypes.c_int, _P, _P])
_max_order = declare("sh_rot_method_max_order", [ctypes.c_int], ctypes.c_int, status=False)
_kernel_available = declare("sh_rot_kernel_available", [ctypes.c_int], ctypes.c_int, status=False)

SH_ROTATE_INVERSE = 1


def method_max_order(method):
    """The largest order a rotation method accepts (docs/ranges.md)."""
    return _max_order(_names.method(method))


def kernel_available(kernel):
    """True if this CPU runs the kernel ("scalar", "unrolled", "sse2", "avx2", "avx512")."""
    return bool(_kernel_available(_names.kernel(kernel)))


def _vectors(coeffs, n2, dtype, what="coeffs"):
    """coeffs as a C-contiguous dtype array of shape (..., n2), and the count of vectors."""
    c = real_array(coeffs, dtype, what)
    if c.ndim < 1 or c.shape[-1] != n2:
        raise ValueError("%s must have shape (..., %d) for this order, not %s" % (what, n2, c.shape))
    return c, int(np.prod(c.shape[:-1], dtype=np.int64))


def _checked_matrix(m, dtype=np.float64):
    """A (3, 3) matrix checked to be a rotation by shlab (sh_rotation_from_matrix),
    returned unchanged as a C-contiguous array of dtype."""
    a = real_array(m, dtype, "matrix")
    if a.shape != (3, 3):
        raise ValueError("matrix must have shape (3, 3), not %s" % (a.shape,))
    Rotation.from_matrix(a.astype(np.float64))
    return a


def _is_matrix(rot):
    return not isinstance(rot, Rotation) and np.shape(rot) == (3, 3)


class Rotator:
    """One immutable rotator per (order, method, precision, kernel,
    convention, threads) (sh_rotator_create): arguments checked, ``auto``
    resolved, per-order tables built; share it between threads.

    method: "auto" (zxzxz up to order 32, halfpi above), or any of "z",
    "ivanic", "zxzxz", "choi", "blanco", "wigner", "reference", "taylor1",
    "taylor1.5", "taylor2", "halfpi", "direct"; precision "double" or
    "float"; kernel "auto", "scalar", "unrolled", "sse2", "avx2", "avx512";
    threads: the high-band stream's threads (≤ 0: every core).
    ``progress(done, total, what)`` (optional) is called from the long steps.
    """

    def __init__(self, order, method="auto", precision="double", kernel="auto", convention="cs", threads=0,
                 progress=None):
        o = _Opts()
        o.order = check_order(order)
        o.method = _names.method_or_auto(method)
        o.prec = _names.precision(precision)
        o.kernel = _names.kernel(kernel)
        o.conv = _names.convention(convention)
        o.threads = int(threads)
        self._progress = _PROGRESS(lambda ctx, d, t, w: progress(d, t, w.decode())) if progress else _PROGRESS()
        o.progress = self._progress
        h = _P()
        _create(ctypes.byref(o), ctypes.byref(h))
        self._h = h
        self.order = _r_int["order"](h)
        self.n2 = self.order * self.order
        self.method = _names.method_name(_r_int["method"](h))
        self.precision = _names.precision_name(_r_int["precision"](h))
        self.kernel = _names.kernel_name(_r_int["kernel"](h))
        self.threads = _r_int["threads"](h)
        self.streams = bool(_r_int["streams"](h))
        self.convention = _names.convention_name(o.conv)

    def __del__(self):
        h = getattr(self, "_h", None)
        if h:
            _free(h)
            self._h = None

    @property
    def handle(self):
        return self._h

    def bytes(self):
        """(bytes the rotator holds, bytes of each plan or call)."""
        per = ctypes.c_size_t()
        total = _r_bytes(self._h, ctypes.byref(per))
        return total, per.value

    def apply(self, coeffs, rotation, inverse=False, out=None):
        """R_sh · coeffs for every vector along the last axis (shape (..., order²)).

        float64 coefficients go through sh_rotator_apply (a Rotation, Euler
        angles or a quaternion; the angles are used) or sh_rotator_apply_matrix
        (a (3, 3) matrix: checked to be a rotation, then given as is).  For a
        float rotator, float32 coefficients go through sh_rotator_apply_matrix_f
        (float matrix, float vectors, one call per vector); float64 ones are
        rotated in float arithmetic and returned as float64.  ``inverse``
        applies R_sh(Rᵀ).  ``out`` may be ``coeffs`` itself (in place)."""
        f32 = self.precision == "float" and np.asarray(coeffs).dtype == np.float32
        c, nvec = _vectors(coeffs, self.n2, np.float32 if f32 else np.float64)
        res = out_array(out, c.shape, c.dtype)
        if nvec == 0:
            return res
        if f32:
            m = _checked_matrix(rotation.matrix if isinstance(rotation, Rotation) else
                                (rotation if _is_matrix(rotation) else as_rotation(rotation).matrix),
                                np.float32)
            if inverse:
                m = np.ascontiguousarray(m.T)
            step = self.n2 * 4
            for k in range(nvec):
                _apply_matrix_f(self._h, m.ctypes.data, c.ctypes.data + k * step, res.ctypes.data + k * step)
            return res
        flags = SH_ROTATE_INVERSE if inverse else 0
        if _is_matrix(rotation):
            m = _checked_matrix(rotation)
            _apply_matrix(self._h, m.ctypes.data, flags, nvec, c.ctypes.data, res.ctypes.data)
        else:
            r = as_rotation(rotation)
            _apply(self._h, ctypes.byref(r.c), flags, nvec, c.ctypes.data, res.ctypes.data)
        return res

    def plan(self):
        """A :class:`Plan` reading this rotator, for one thread."""
        return Plan(self)


class Plan:
    """A per-thread plan of a rotator (sh_rotator_plan): set a rotation once,
    apply it to many vectors, or run batches.  Use from one thread at a time."""

    def __init__(self, rotator):
        if not isinstance(rotator, Rotator):
            raise TypeError("Plan(rotator): a shlab.Rotator")
        self.rotator = rotator  # kept alive: the plan reads it
        h = _P()
        _plan(rotator.handle, ctypes.byref(h))
        self._h = h
        self.order, self.n2 = rotator.order, rotator.n2
        self.is_float = rotator.precision == "float"
        self.kernel = _names.kernel_name(_plan_kernel(h))

    def __del__(self):
        h = getattr(self, "_h", None)
        if h:
            _plan_free(h)
            self._h = None

    def set(self, rotation):
        """Set the rotation: a Rotation (sh_rot_plan_set), a (3, 3) matrix
        (checked, then sh_rot_plan_set_matrix; a float32 matrix on a float
        plan: sh_rot_plan_set_matrix_f), a (4,) quaternion
        (sh_rot_plan_set_quat, any non-zero norm; float32: _f) or (3,) Euler
        angles.  Returns self."""
        if isinstance(rotation, Rotation):
            _plan_set(self._h, ctypes.byref(rotation.c))
            return self
        a = np.asarray(rotation)
        f32 = self.is_float and a.dtype == np.float32
        dt = np.float32 if f32 else np.float64
        if a.shape == (3, 3):
            m = _checked_matrix(a, dt)
            (_plan_set_matrix_f if f32 else _plan_set_matrix)(self._h, m.ctypes.data)
        elif a.shape == (4,):
            q = real_array(a, dt, "quaternion")
            (_plan_set_quat_f if f32 else _plan_set_quat)(self._h, q.ctypes.data)
        else:
            _plan_set(self._h, ctypes.byref(as_rotation(rotation).c))
        return self

    def apply(self, coeffs, out=None):
        """R_sh · coeffs (shape (..., order²)) for the rotation set; float32
        vectors on a float plan go through sh_rot_plan_apply_f."""
        f32 = self.is_float and np.asarray(coeffs).dtype == np.float32
        c, nvec = _vectors(coeffs, self.n2, np.float32 if f32 else np.float64)
        res = out_array(out, c.shape, c.dtype)
        fn, size = (_plan_apply_f, 4) if f32 else (_plan_apply, 8)
        for k in range(nvec):
            fn(self._h, c.ctypes.data + k * self.n2 * size, res.ctypes.data + k * self.n2 * size)
        return res

    def _soa(self, coeffs, what):
        dt = np.float32 if self.is_float else np.float64
        c = np.asarray(coeffs)
        if c.dtype.kind == "f" and c.dtype != dt:
            raise TypeError("a %s plan takes %s batches (the %s forms), not %s"
                            % ("float" if self.is_float else "double", np.dtype(dt).name,
                               "_f" if self.is_float else "double", c.dtype))
        c = real_array(c, dt, what)
        if c.ndim != 2 or c.shape[0] != self.n2:
            raise ValueError("%s must have shape (order², K) = (%d, K): coefficient i of vector k at [i, k] "
                             "(structure of arrays), not %s" % (what, self.n2, c.shape))
        return c, c.shape[1]

    def apply_many(self, coeffs_soa, out=None):
        """The rotation set applied to K vectors held as structure of arrays:
        shape (order², K), coefficient i of vector k at [i, k] (so
        ``coeffs.T`` of a (K, order²) stack; pass a C-contiguous array to
        avoid a copy).  float64 for double plans, float32 for float plans."""
        c, K = self._soa(coeffs_soa, "coeffs_soa")
        res = out_array(out, c.shape, c.dtype)
        _many["apply_many_f" if self.is_float else "apply_many"](self._h, K, c.ctypes.data, res.ctypes.data)
        return res

    def rotate_many(self, rotations, coeffs_soa, out=None):
        """K rotations applied to K vectors: vector k by rotation k.

        rotations: (K, 3, 3) matrices, (K, 4) quaternions (w, x, y, z), or a
        sequence of K Rotations (their matrices); they are copied into the C
        layout (entry j of rotation k at [j·K + k]).  coeffs_soa: shape
        (order², K), as apply_many.  After this the plan has no rotation set."""
        c, K = self._soa(coeffs_soa, "coeffs_soa")
        dt = c.dtype
        if isinstance(rotations, (list, tuple)) and rotations and isinstance(rotations[0], Rotation):
            rotations = np.stack([r.matrix for r in rotations])
        r = real_array(rotations, np.float64, "rotations")
        if r.shape == (K, 3, 3):
            for k in range(K):
                _checked_matrix(r[k])
            soa = np.ascontiguousarray(r.reshape(K, 9).T, dtype=dt)
            name = "rotate_many"
        elif r.shape == (K, 4):
            soa = np.ascontiguousarray(r.T, dtype=dt)
            name = "rotate_many_quat"
        else:
            raise ValueError("rotations must have shape (K, 3, 3) or (K, 4) with K = %d (the vectors), not %s"
                             % (K, r.shape))
        res = out_array(out, c.shape, dt)
        _many[name + ("_f" if self.is_float else "")](self._h, K, soa.ctypes.data, c.ctypes.data, res.ctypes.data)
        return res

    def blocks(self):
        """The blocks of the rotation set: a list of (2l+1)×(2l+1) arrays, l = 0..order-1."""
        n = self.order
        flat = np.empty(n * (2 * n - 1) * (2 * n + 1) // 3 if n else 0)
        _plan_blocks(self._h, flat.ctypes.data)
        out, off = [], 0
        for l in range(n):
            w = 2 * l + 1
            out.append(flat[off:off + w * w].reshape(w, w))
            off += w * w
        return out

    def matrix(self):
        """The dense order²×order² SH rotation matrix of the rotation set."""
        n = self.order
        flat = np.concatenate([b.ravel() for b in self.blocks()])
        dense = np.empty((n * n, n * n))
        _blocks_to_dense(n, flat.ctypes.data, dense.ctypes.data)
        return dense


def rotation_matrix(order, rotation, method="auto", convention="cs", precision="double"):
    """The dense order²×order² matrix R_sh of a rotation (block diagonal),
    by a plan of the given method."""
    return Rotator(order, method=method, precision=precision, convention=convention, threads=1).plan() \
        .set(rotation).matrix()


class Stream:
    """The threaded all-band stream for high orders (sh_rot_stream_*): the
    halfpi method generated band by band with O(order) scratch per thread;
    results are bit for bit the same for any number of threads (≤ 0: every
    core)."""

    def __init__(self, order, convention="cs", threads=0):
        self.order = check_order(order)
        self.n2 = self.order * self.order
        self.convention = _names.convention_name(_names.convention(convention))
        h = _P()
        _stream_create(self.order, _names.convention(convention), int(threads), ctypes.byref(h))
        self._h = h
        self.threads = _stream_threads(h)

    def __del__(self):
        h = getattr(self, "_h", None)
        if h:
            _stream_free(h)
            self._h = None

    def apply(self, rotations, coeffs, inverse=False):
        """Every rotation applied to every vector: rotations is one rotation or
        a sequence of nrot; coeffs has shape (order²,) or (nvec, order²)
        (float64).  Returns shape (nrot, nvec, order²) — squeezed to the
        input's shape for a single rotation given alone."""
        if isinstance(rotations, (list, tuple)) and rotations and all(isinstance(r, Rotation) for r in rotations):
            single, rots = False, list(rotations)
        elif isinstance(rotations, Rotation):
            single, rots = True, [rotations]
        else:
            a = real_array(rotations, np.float64, "rotations")
            if a.shape in ((3, 3), (4,), (3,)):
                single, rots = True, [as_rotation(a)]
            elif a.ndim == 3 and a.shape[1:] == (3, 3) or a.ndim == 2 and a.shape[1] in (3, 4):
                single, rots = False, [as_rotation(x) for x in a]
            else:
                raise ValueError("rotations: a rotation, a sequence of Rotations, or an array of shape (K, 3, 3) "
                                 "matrices, (K, 4) quaternions or (K, 3) Euler angles; not shape %s" % (a.shape,))
        c, nvec = _vectors(coeffs, self.n2, np.float64)
        arr = (CRotation * max(1, len(rots)))(*[r.c for r in rots])
        res = np.empty((len(rots), nvec, self.n2))
        if rots and nvec:
            _stream_apply(self._h, len(rots), arr, 1 if inverse else 0, nvec, c.ctypes.data, res.ctypes.data)
        return res.reshape(c.shape) if single else res


def rotate_band(l, rotation, coeffs, convention="cs", inverse=False):
    """Band l alone (sh_rot_band_apply, halfpi's kernel, O(l²)): coeffs has
    shape (..., 2l+1) (float64), the band's values m = −l..l."""
    if isinstance(l, bool) or not isinstance(l, (int, np.integer)):
        raise TypeError("l must be an int")
    if l < 0:
        raise ValueError("band l must be >= 0, not %d" % l)
    c, nvec = _vectors(coeffs, 2 * int(l) + 1, np.float64)
    res = np.empty_like(c)
    if nvec:
        _band_apply(int(l), _names.convention(convention), ctypes.byref(as_rotation(rotation).c),
                    1 if inverse else 0, nvec, c.ctypes.data, res.ctypes.data)
    return res
