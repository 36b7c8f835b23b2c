"""Projection onto SH: analytic lights (sh_light_*), their closed forms,
projection rules (sh_project_ex), Python functions, and environment images
(sh_project_image_ex) from numpy arrays or EXR files.

Rules: "quad" (Gauss-Legendre in cosθ × uniform φ, exact for band-limited
functions; ``samples`` = θ nodes), "mc" (Green's stratified Monte Carlo),
"random", "qmc" (Sobol); samples <= 0 is the rule's default; every rule is
reproducible for a given seed.  Results are float64 arrays of order²
coefficients (c[i] = ∫ f y_i dΩ).
"""
import ctypes
import os

import numpy as np

from . import _names
from ._lib import check_order, cstr, declare, finite
from .image import CImage, _exr_read, _image_free, c_image, planar

__all__ = ["Light", "project_light", "project_function", "project_image", "project_exr", "green_reference",
           "cap_zonal", "lobe_zonal", "rule_samples_used", "image_max_order"]

_P = ctypes.c_void_p
SPHERE_FN = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.c_double, ctypes.c_double,
                             ctypes.c_void_p)
_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_char_p)


class CLight(ctypes.Structure):
    """ctypes mirror of sh_light (src/shlab/project.h)."""
    _fields_ = [("kind", ctypes.c_int), ("p", ctypes.c_double * 2)]


class _RunOpts(ctypes.Structure):
    """ctypes mirror of sh_run_opts."""
    _fields_ = [("nthreads", ctypes.c_int), ("progress", _PROGRESS), ("progress_ctx", ctypes.c_void_p)]


_LP = ctypes.POINTER(CLight)
_light_parse = declare("sh_light_parse", [ctypes.c_char_p, ctypes.c_int, _LP])
_light_eval = declare("sh_light_eval", [_LP, _P, ctypes.c_double, ctypes.c_double], ctypes.c_double,
                      status=False)
_light_has_cf = declare("sh_light_has_closed_form", [_LP], ctypes.c_int, status=False)
_light_cf = declare("sh_light_closed_form", [_LP, ctypes.c_int, ctypes.c_int, _P])
_project_ex = declare("sh_project_ex", [ctypes.c_int, ctypes.c_int, SPHERE_FN, _P, ctypes.c_int, ctypes.c_long,
                                        ctypes.c_ulong, ctypes.POINTER(_RunOpts), _P])
_project_image_ex = declare("sh_project_image_ex", [ctypes.POINTER(CImage), ctypes.c_int, ctypes.c_int,
                                                    ctypes.c_int, ctypes.POINTER(_RunOpts), _P])
_image_max_order = declare("sh_image_max_order", [ctypes.POINTER(CImage), ctypes.c_int], ctypes.c_int,
                           status=False)
_image_check_order = declare("sh_image_check_order", [ctypes.POINTER(CImage), ctypes.c_int, ctypes.c_int])
_green_reference = declare("sh_green_reference", [ctypes.c_int, ctypes.c_int, ctypes.c_double, _P])
_cap_zonal = declare("sh_cap_zonal", [ctypes.c_double, ctypes.c_int, _P])
_lobe_zonal = declare("sh_lobe_zonal", [ctypes.c_double, ctypes.c_int, _P])
_samples_used = declare("sh_rule_samples_used", [ctypes.c_int, ctypes.c_long], ctypes.c_long, status=False)
# the C adaptor sh_light_fn (ctx: const sh_light *), as a function pointer
_light_fn = ctypes.cast(declare("sh_light_fn", [], ctypes.c_double, status=False), SPHERE_FN)


def _opts(threads):
    o = _RunOpts()
    o.nthreads = int(threads)
    return o


class Light:
    """An analytic light (sh_light).  Make one from shlab's spec text
    (:meth:`parse`: "green", "cap:T", "cie-overcast", "cie-clear:TH,PH",
    "cie-partly:TH,PH", "const:V", "lobe:E"; angles in radians unless
    degrees=True) or the named constructors."""

    __slots__ = ("_c", "spec")

    def __init__(self, spec, degrees=False):
        self._c = CLight()
        self.spec = spec
        _light_parse(cstr(spec, "light spec"), 1 if degrees else 0, ctypes.byref(self._c))

    parse = classmethod(lambda cls, spec, degrees=False: cls(spec, degrees))

    @classmethod
    def green(cls):
        """Green (2003) Figure 7's two-lobe example light."""
        return cls("green")

    @classmethod
    def cap(cls, t):
        """1 inside the cap of half-angle t (radians) about +z, 0 outside."""
        return cls("cap:%.17g" % finite(t, "t"))

    @classmethod
    def const(cls, v):
        return cls("const:%.17g" % finite(v, "v"))

    @classmethod
    def lobe(cls, e):
        """max(0, cos θ)^e."""
        return cls("lobe:%.17g" % finite(e, "e"))

    @classmethod
    def cie_overcast(cls):
        return cls("cie-overcast")

    @classmethod
    def cie_clear(cls, theta, phi):
        """CIE clear sky, sun at (theta, phi) radians."""
        return cls("cie-clear:%.17g,%.17g" % (finite(theta, "theta"), finite(phi, "phi")))

    @classmethod
    def cie_partly(cls, theta, phi):
        return cls("cie-partly:%.17g,%.17g" % (finite(theta, "theta"), finite(phi, "phi")))

    def __repr__(self):
        return "Light(%r)" % self.spec

    @property
    def has_closed_form(self):
        """True for cap, const and lobe."""
        return bool(_light_has_cf(ctypes.byref(self._c)))

    def __call__(self, dirs):
        """The light's value at unit vectors dirs (shape (..., 3)), shape (...)."""
        from .basis import angles_from_dir
        d = np.ascontiguousarray(dirs, dtype=np.float64)
        if d.ndim < 1 or d.shape[-1] != 3:
            raise ValueError("dirs must have shape (..., 3), not %s" % (d.shape,))
        th, ph = angles_from_dir(d)
        d2, th, ph = d.reshape(-1, 3), th.ravel(), ph.ravel()
        u = d2 / np.linalg.norm(d2, axis=1)[:, None]
        u = np.ascontiguousarray(u)
        out = np.array([_light_eval(ctypes.byref(self._c), u.ctypes.data + 24 * k, th[k], ph[k])
                        for k in range(u.shape[0])])
        return out.reshape(d.shape[:-1])

    def closed_form(self, order, convention="cs"):
        """The exact coefficients (cap, const, lobe; others raise shlab.Error SH_ENOTSUP)."""
        order = check_order(order)
        out = np.empty(order * order)
        _light_cf(ctypes.byref(self._c), order, _names.convention(convention), out.ctypes.data)
        return out


def project_light(light, order, convention="cs", rule="quad", samples=0, seed=0, threads=1):
    """Project an analytic light by a rule (sh_project_ex with sh_light_fn,
    all in C).  threads: 0 for every core (results do not depend on it)."""
    if isinstance(light, str):
        light = Light(light)
    if not isinstance(light, Light):
        raise TypeError("light must be a shlab.Light or a spec string")
    order = check_order(order)
    out = np.empty(order * order)
    o = _opts(threads)
    _project_ex(order, _names.convention(convention), _light_fn, ctypes.cast(ctypes.byref(light._c), _P),
                _names.rule(rule), int(samples), int(seed), ctypes.byref(o), out.ctypes.data)
    return out


def project_function(f, order, convention="cs", rule="quad", samples=0, seed=0):
    """Project a Python function f(dir, theta, phi) -> float (dir a (3,)
    unit vector) by a rule (sh_project_ex, one thread).  An exception raised
    by f is re-raised after the C call returns."""
    order = check_order(order)
    out = np.empty(order * order)
    failure = []

    def cb(d, th, ph, ctx):
        if failure:
            return 0.0
        try:
            return float(f(np.array([d[0], d[1], d[2]]), th, ph))
        except BaseException as e:  # noqa: B902 — re-raised below
            failure.append(e)
            return 0.0

    fn = SPHERE_FN(cb)
    o = _opts(1)
    _project_ex(order, _names.convention(convention), fn, None, _names.rule(rule), int(samples), int(seed),
                ctypes.byref(o), out.ctypes.data)
    if failure:
        raise failure[0]
    return out


def _project_cimage(c, layout, order, convention, threads, check):
    lay = _names.layout(layout)
    order = check_order(order)
    if check:
        _image_check_order(ctypes.byref(c), lay, order)
    out = np.empty((c.nchan, order * order))
    o = _opts(threads)
    _project_image_ex(ctypes.byref(c), lay, order, _names.convention(convention), ctypes.byref(o),
                      out.ctypes.data)
    return out


def image_max_order(image, layout="latlong"):
    """The largest order an image of this size carries (sh_image_max_order)."""
    p, _ = planar(image)
    return _image_max_order(ctypes.byref(c_image(p)), _names.layout(layout))


def project_image(image, order, layout="latlong", convention="cs", threads=1, check=True):
    """Project each channel of an environment image (exact pixel solid angles).

    image: (H, W) or (H, W, C) array (see shlab.image for when it is passed
    without a copy); layout "latlong" (W×H equirectangular, φ from the left,
    θ from the top) or "probe" (angle map).  Returns (order²,) for a 2-D image,
    else (C, order²).  check: refuse (shlab.Error) an order above what the
    image carries (sh_image_check_order), as the CLI does."""
    p, flat = planar(image)
    out = _project_cimage(c_image(p), layout, order, convention, threads, check)
    return out[0] if flat else out


def project_exr(path, order, layout="latlong", convention="cs", threads=1, check=True):
    """Read an EXR environment map and project each channel: (C, order²)."""
    c = CImage()
    fb = ctypes.c_int()
    _exr_read(cstr(os.fspath(path), "path"), ctypes.byref(c), ctypes.byref(fb))
    try:
        return _project_cimage(c, layout, order, convention, threads, check)
    finally:
        _image_free(ctypes.byref(c))


def green_reference(order, convention="cs", tol=1e-12):
    """Accurate projection of Green's Figure 7 light (order <= 64)."""
    order = check_order(order)
    out = np.empty(order * order)
    _green_reference(order, _names.convention(convention), finite(tol, "tol"), out.ctypes.data)
    return out


def cap_zonal(t, order):
    """Zonal closed form of the cap of half-angle t: z_l, l = 0..order-1."""
    order = check_order(order)
    out = np.empty(order)
    _cap_zonal(finite(t, "t"), order, out.ctypes.data)
    return out


def lobe_zonal(e, order):
    """Zonal closed form of max(0, cosθ)^e: z_l, l = 0..order-1."""
    order = check_order(order)
    out = np.empty(order)
    _lobe_zonal(finite(e, "e"), order, out.ctypes.data)
    return out


def rule_samples_used(rule, samples):
    """The number of samples a rule really uses for ``samples``."""
    return _samples_used(_names.rule(rule), int(samples))
