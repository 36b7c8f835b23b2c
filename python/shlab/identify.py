"""Other people's SH conventions and their identification (src/shlab/convention.h):
the library side of ``shlab identify`` and of ``shlab convert --from SPEC --to SPEC``.

- :class:`Convention` wraps a descriptor (sh_conv): ``Convention.parse(spec)``,
  ``str()`` the full spec (sh_conv_format), ``.preset``, equality field by field.
- :func:`convert_convention`, :func:`to_shlab`, :func:`from_shlab` convert
  coefficient vectors between conventions (sh_conv_convert / _to_shlab /
  _from_shlab); :func:`eval_convention` evaluates a user's basis
  (sh_conv_eval_dir).  Complex layouts are interleaved doubles (re, im), as
  in the C API: a complex vector of N entries is 2N float64 values (a numpy
  complex array ``z`` gives them as ``z.view(np.float64)``).
- :func:`identify_basis` (the user's basis at :func:`fixture_directions`) and
  :func:`identify_projection` (the user's coefficients of the fixture's light,
  :func:`fixture_light`) name the convention (sh_identify_basis /
  _projection); the result has the fields of ``shlab identify --format json``.
"""
import ctypes

import numpy as np

from ._lib import cstr, declare, finite, real_array

__all__ = ["Convention", "convert_convention", "to_shlab", "from_shlab", "eval_convention", "identify_basis",
           "identify_projection", "fixture_directions", "fixture_light", "fixture_light_coeffs",
           "IdentifyResult", "Candidate", "NDIRS", "MAX_ORDER"]

NDIRS = 32          # SH_IDENTIFY_NDIRS
NLIGHTS = 3         # SH_IDENTIFY_NLIGHTS
MAX_ORDER = 16      # SH_IDENTIFY_MAX_ORDER
_MAX_ALIASES = 16   # SH_IDENTIFY_MAX_ALIASES
_VERDICTS = ("identified", "ambiguous", "none")
_KINDS = ("real", "complex", "complex-half")
_NORMS = ("ortho", "4pi", "schmidt", "sn3d", "n3d", "fuma")
_INDEXES = ("acn", "mdesc", "cossin", "fuma-order")


class CConv(ctypes.Structure):
    """ctypes mirror of sh_conv."""
    _fields_ = [("kind", ctypes.c_int), ("cs", ctypes.c_int), ("norm", ctypes.c_int), ("index", ctypes.c_int),
                ("neg_cos", ctypes.c_int), ("axes", ctypes.c_int)]


class CCandidate(ctypes.Structure):
    """ctypes mirror of sh_id_candidate."""
    _fields_ = [("conv", CConv), ("naliases", ctypes.c_int), ("aliases", CConv * _MAX_ALIASES),
                ("order", ctypes.c_int), ("residual", ctypes.c_double),
                ("band_residual", ctypes.c_double * MAX_ORDER), ("fits", ctypes.c_int),
                ("fits_through", ctypes.c_int)]


class CResult(ctypes.Structure):
    """ctypes mirror of sh_id_result."""
    _fields_ = [("verdict", ctypes.c_int), ("ncand", ctypes.c_int), ("cand", ctypes.POINTER(CCandidate)),
                ("needs_order", ctypes.c_int), ("needs_basis", ctypes.c_int), ("tol", ctypes.c_double)]


class _IdText(ctypes.Structure):
    """ctypes mirror of sh_id_text: what `shlab identify` says of a result."""
    _fields_ = [("convention", ctypes.c_char * 96), ("to_shlab", ctypes.c_char * 512),
                ("from_shlab", ctypes.c_char * 512), ("needs", ctypes.c_char * 160)]


_P = ctypes.c_void_p
_CP = ctypes.POINTER(CConv)
_INT4 = ctypes.c_int * 4
_parse = declare("sh_conv_parse", [ctypes.c_char_p, _CP])
_format = declare("sh_conv_format", [_CP, ctypes.c_char_p, ctypes.c_size_t], ctypes.c_char_p, status=False)
_preset = declare("sh_conv_preset", [_CP], ctypes.c_char_p, status=False)
_check = declare("sh_conv_check", [_CP, ctypes.c_int])
_ndoubles = declare("sh_conv_ndoubles", [_CP, ctypes.c_int], ctypes.c_size_t, status=False)
_order_of = declare("sh_conv_order_of", [_CP, ctypes.c_size_t, ctypes.POINTER(ctypes.c_int)])
_eval_dir = declare("sh_conv_eval_dir", [_CP, ctypes.c_int, _P, _P])
_to_shlab = declare("sh_conv_to_shlab", [_CP, ctypes.c_int, _P, _P])
_from_shlab = declare("sh_conv_from_shlab", [_CP, ctypes.c_int, _P, _P])
_convert = declare("sh_conv_convert", [_CP, _CP, ctypes.c_int, _P, _P])
_id_basis = declare("sh_identify_basis", [ctypes.c_int, _P, ctypes.c_size_t, _P, ctypes.c_int, ctypes.c_double,
                                          ctypes.POINTER(CResult)])
_id_proj = declare("sh_identify_projection", [ctypes.c_size_t, _P, _P, ctypes.c_int, ctypes.c_int,
                                              ctypes.c_double, ctypes.POINTER(CResult)])
_id_free = declare("sh_identify_free", [ctypes.POINTER(CResult)], None, status=False)
_identify_text = declare("sh_identify_text", [ctypes.POINTER(CResult), ctypes.c_char_p, ctypes.POINTER(_IdText)], None,
                         status=False)
_id_dirs = declare("sh_identify_directions", [_P, _P], None, status=False)
_id_light = declare("sh_identify_light", [_P, _P, _P], None, status=False)
_id_light_coeffs = declare("sh_identify_light_coeffs", [ctypes.c_int, _P])


def available():
    """True if the loaded libshlab has the convention API (convention.h)."""
    return not getattr(_parse, "missing", False)


# ------------------------------------------------------------- Convention
class Convention:
    """A user's SH convention (sh_conv): kind, phase, normalisation, index
    order, the function of m < 0 and axes (docs/CONVENTIONS.md, "Other
    conventions").

    ``Convention.parse("ambix")`` or ``Convention("real,nocs,sn3d")`` (a spec
    string or a preset), ``Convention()`` shlab's own.  ``str(c)`` is the full
    spec with every field written (sh_conv_format), ``c.preset`` the preset
    name it equals field by field (or None).  Equality is field by field:
    sn3d and schmidt are the same functions but different descriptors."""

    def __init__(self, spec="cs"):
        if isinstance(spec, Convention):
            self._c = CConv.from_buffer_copy(spec._c)
            return
        if isinstance(spec, CConv):
            self._c = CConv.from_buffer_copy(spec)
            return
        c = CConv()
        _parse(cstr(spec, "convention spec"), ctypes.byref(c))
        self._c = c

    @classmethod
    def parse(cls, spec):
        """The descriptor of a spec string (shlab.Error naming the bad token)."""
        return cls(spec)

    @classmethod
    def shlab(cls):
        """shlab's own convention (real, cs, ortho, acn, neg-sin, z-up)."""
        return cls("cs")

    def __str__(self):
        buf = ctypes.create_string_buffer(96)
        return _format(ctypes.byref(self._c), buf, 96).decode()

    def __repr__(self):
        return "Convention(%r)" % str(self)

    @property
    def preset(self):
        """The preset name (cs, nocs, 4pi, schmidt, ambix, fuma, healpix) this
        descriptor equals field by field, or None."""
        p = _preset(ctypes.byref(self._c))
        return p.decode() if p else None

    def _key(self):
        c = self._c
        return (c.kind, c.cs, c.norm, c.index, c.neg_cos, c.axes)

    def __eq__(self, other):
        if isinstance(other, str):
            try:
                other = Convention(other)
            except Exception:
                return False
        if not isinstance(other, Convention):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    kind = property(lambda self: _KINDS[self._c.kind], doc="real, complex or complex-half")
    cs = property(lambda self: bool(self._c.cs), doc="True: the Condon-Shortley phase")
    norm = property(lambda self: _NORMS[self._c.norm], doc="ortho, 4pi, schmidt, sn3d, n3d or fuma")
    index = property(lambda self: _INDEXES[self._c.index], doc="acn, mdesc, cossin or fuma-order")
    neg_cos = property(lambda self: bool(self._c.neg_cos), doc="True: cos(|m|φ) for m < 0")
    axes = property(lambda self: self._c.axes, doc="0..47, 0 = z-up (convention.h)")

    def check(self, order):
        """shlab.Error unless valid at ``order`` (FuMa: order <= 4)."""
        _check(ctypes.byref(self._c), _int(order, "order"))

    def ndoubles(self, order):
        """Doubles in a vector of this order: n² real, 2n² complex, n(n+1) complex-half."""
        self.check(order)
        return int(_ndoubles(ctypes.byref(self._c), int(order)))

    def order_of(self, ndoubles):
        """The order whose vector has ``ndoubles`` doubles (shlab.Error if none)."""
        o = ctypes.c_int()
        _order_of(ctypes.byref(self._c), _int(ndoubles, "ndoubles"), ctypes.byref(o))
        return o.value


def _conv(spec, what="convention"):
    if isinstance(spec, Convention):
        return spec
    if not isinstance(spec, str):
        raise TypeError("%s must be a spec string or a Convention, not %s" % (what, type(spec).__name__))
    return Convention(spec)


def _int(x, what):
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise TypeError("%s must be an int, not %s" % (what, type(x).__name__))
    if not 0 <= int(x) < 2**31:
        raise ValueError("%s %d is out of range" % (what, x))
    return int(x)


def _doubles(a, what, finite_only=False):
    """A C-contiguous float64 copy-or-view of a real array with at least one
    axis; complex arrays are refused with the way to interleave them (and
    non-finite values with ``finite_only``)."""
    arr = np.asarray(a)
    if arr.dtype.kind == "c":
        raise TypeError("%s: complex numbers are interleaved doubles (re, im) here; pass z.view(np.float64) "
                        "of a C-contiguous complex128 array" % what)
    arr = real_array(arr, np.float64, what)
    if arr.ndim < 1:
        raise ValueError("%s must have at least one axis" % what)
    if finite_only and not np.all(np.isfinite(arr)):
        raise ValueError("%s holds non-finite values" % what)
    return arr


def _order_for(conv, n, order, what):
    """The order of a vector of n doubles in ``conv`` (checked against ``order`` if given)."""
    if order is None:
        return conv.order_of(n)
    want = conv.ndoubles(order)
    if want != n:
        raise ValueError("%s: the last axis has %d entries; %s at order %d needs %d"
                         % (what, n, conv, int(order), want))
    return int(order)


def _map(fn, arr, nout):
    flat = arr.reshape(-1, arr.shape[-1])
    out = np.empty((flat.shape[0], nout))
    for k in range(flat.shape[0]):
        fn(flat[k].ctypes.data, out[k].ctypes.data)
    return out.reshape(arr.shape[:-1] + (nout,))


def convert_convention(coeffs, from_spec, to_spec, order=None):
    """``coeffs`` (shape (..., ndoubles of from_spec)) converted to ``to_spec``
    (sh_conv_convert), keeping the represented function; the order from the
    last axis's length unless given.  Returns a new float64 array."""
    a, b = _conv(from_spec, "from_spec"), _conv(to_spec, "to_spec")
    arr = _doubles(coeffs, "coeffs")
    n = _order_for(a, arr.shape[-1], order, "coeffs")
    b.check(n)
    return _map(lambda i, o: _convert(ctypes.byref(a._c), ctypes.byref(b._c), n, i, o), arr, b.ndoubles(n))


def to_shlab(coeffs, spec, order=None):
    """The user's coefficients ``coeffs`` (..., ndoubles) in convention ``spec``
    as shlab's (..., order²) (sh_conv_to_shlab)."""
    c = _conv(spec, "spec")
    arr = _doubles(coeffs, "coeffs")
    n = _order_for(c, arr.shape[-1], order, "coeffs")
    return _map(lambda i, o: _to_shlab(ctypes.byref(c._c), n, i, o), arr, n * n)


def from_shlab(coeffs, spec):
    """shlab's coefficients (..., order²) as the user's in ``spec``
    (..., ndoubles) (sh_conv_from_shlab)."""
    c = _conv(spec, "spec")
    arr = _doubles(coeffs, "coeffs")
    k = int(round(np.sqrt(arr.shape[-1])))
    if k < 1 or k * k != arr.shape[-1]:
        raise ValueError("coeffs: the last axis has %d entries, not order² for an order n >= 1" % arr.shape[-1])
    c.check(k)
    return _map(lambda i, o: _from_shlab(ctypes.byref(c._c), k, i, o), arr, c.ndoubles(k))


def eval_convention(spec, order, dirs):
    """The user's basis of ``spec`` at directions ``dirs`` (..., 3) in the
    user's coordinates (sh_conv_eval_dir, which normalises them): shape
    (..., ndoubles); complex kinds give interleaved (re, im)."""
    c = _conv(spec, "spec")
    order = _int(order, "order")
    d = real_array(dirs, np.float64, "dirs")
    if d.ndim < 1 or d.shape[-1] != 3:
        raise ValueError("dirs must have shape (..., 3), not %s" % (d.shape,))
    c.check(order)
    return _map(lambda i, o: _eval_dir(ctypes.byref(c._c), order, i, o), d, c.ndoubles(order))


# ---------------------------------------------------------------- fixture
def fixture_directions(exact=False):
    """The 32 fixture directions (sh_identify_directions) as a (32, 3) array
    of unit vectors, in the order a basis is given to :func:`identify_basis`.
    With ``exact=True`` also a (32, 4) int array of (a, b, c, n): d = (a, b, c)/n."""
    d = np.empty((NDIRS, 3))
    ex = np.zeros((NDIRS, 4), dtype=np.intc)
    _id_dirs(d.ctypes.data, ex.ctypes.data)
    return (d, ex.astype(int)) if exact else d


def fixture_light():
    """The fixture's light f = Σ_j w_j δ(d_j) (sh_identify_light): (dirs (3, 3), weights (3,))."""
    d = np.empty((NLIGHTS, 3))
    w = np.empty(NLIGHTS)
    _id_light(d.ctypes.data, w.ctypes.data, None)
    return d, w


def fixture_light_coeffs(order):
    """shlab's projection of the fixture's light to ``order`` (<= 16):
    c_i = Σ_j w_j y_i(d_j) (sh_identify_light_coeffs)."""
    order = _int(order, "order")
    c = np.empty(max(1, order * order))
    _id_light_coeffs(order, c.ctypes.data)
    return c[:order * order]


# ----------------------------------------------------------------- result
class _Fields:
    def __init__(self, fields, extra):
        self._fields = fields
        for k, v in fields.items():
            setattr(self, k, v)
        for k, v in extra.items():
            setattr(self, k, v)

    def __getitem__(self, key):
        return self._fields[key]

    def __contains__(self, key):
        return key in self._fields

    def keys(self):
        return self._fields.keys()


class Candidate(_Fields):
    """One class of conventions that fits (or the nearest): the fields of a
    ``candidates`` entry of ``shlab identify --format json``: convention (the
    full spec), preset ("" if none), aliases (the other members' specs,
    space-separated), fits, fits_through_order, band_residuals (bands 0..L
    relative RMS, "%.3g" space-separated) and residual.  Also: conv
    (:class:`Convention`), alias_conventions (list of them), order, and
    band_residual_values (the numbers)."""

    def as_dict(self):
        return dict(self._fields)

    def __repr__(self):
        return "Candidate(%r)" % self._fields


class IdentifyResult(_Fields):
    """The verdict, with the fields of ``shlab identify --format json``:
    input ("basis" or "projection"), order, tolerance, verdict ("identified",
    "ambiguous" or "none"), and when identified convention, to_shlab and
    from_shlab (the ``shlab convert`` commands the CLI prints), otherwise
    needs (what decides, the CLI's sentence), and candidates (list of
    :class:`Candidate`, best first).  ``as_dict()`` gives the JSON object.
    Also: identified (bool), conv (the identified :class:`Convention` or
    None), needs_order, needs_basis."""

    def as_dict(self):
        d = dict(self._fields)
        d["candidates"] = [c.as_dict() for c in self._fields["candidates"]]
        return d

    def __repr__(self):
        return "IdentifyResult(%r)" % self.as_dict()


def _candidate(k):
    conv = Convention(k.conv)
    aliases = [Convention(k.aliases[i]) for i in range(k.naliases)]
    br = [k.band_residual[l] for l in range(k.order)]
    fields = {"convention": str(conv), "preset": conv.preset or "", "aliases": " ".join(map(str, aliases)),
              "fits": bool(k.fits), "fits_through_order": k.fits_through,
              "band_residuals": " ".join("%.3g" % x for x in br), "residual": k.residual}
    return Candidate(fields, {"conv": conv, "alias_conventions": aliases, "order": k.order,
                              "band_residual_values": np.array(br)})


def _result(r, source, file):
    """The JSON object of cmd_identify.c's result_json, from sh_id_result."""
    cands = [_candidate(r.cand[i]) for i in range(r.ncand)]
    f = {"input": source, "order": cands[0].order if cands else 0, "tolerance": r.tol,
         "verdict": _VERDICTS[r.verdict]}
    conv = None
    t = _IdText()
    _identify_text(ctypes.byref(r), str(file).encode(), ctypes.byref(t))  # the CLI's own sentences
    if r.verdict == 0:
        conv = cands[0].conv
        f["convention"] = t.convention.decode()
        f["to_shlab"] = t.to_shlab.decode()
        f["from_shlab"] = t.from_shlab.decode()
    if t.needs:
        f["needs"] = t.needs.decode()
    f["candidates"] = cands
    return IdentifyResult(f, {"identified": r.verdict == 0, "conv": conv, "needs_order": r.needs_order,
                              "needs_basis": bool(r.needs_basis)})


def _id_args(order, tol):
    if order is None:
        o = 0
    else:
        o = _int(order, "order")
        if o == 0:
            raise ValueError("order must be >= 1 (None: from the count of numbers)")
    return o, finite(tol, "tol")


def _run(call, source, file):
    r = CResult()
    try:
        call(ctypes.byref(r))
        return _result(r, source, file)
    finally:
        _id_free(ctypes.byref(r))


def identify_basis(values, order=None, tol=1e-4, file="FILE"):
    """Name the convention of a basis from its values at the 32 fixture
    directions (sh_identify_basis), as ``shlab identify --basis``.

    values: shape (32, per_dir), row j the user's basis vector at
    ``fixture_directions()[j]`` (given to the user's code as it is, in the
    user's coordinates); per_dir = n² (real), 2n² (complex, re,im) or n(n+1)
    (complex-half).  order: None reads it from per_dir (every kind whose
    length matches).  tol: the relative RMS residual a fit may have.
    file: the name put in the result's to_shlab command (the CLI puts its
    --basis file there).  Returns an :class:`IdentifyResult`."""
    v = _doubles(values, "values", finite_only=True)
    if v.ndim != 2 or v.shape[0] != NDIRS or v.shape[1] < 1:
        raise ValueError("values must have shape (%d, per_dir): one row per fixture direction, not %s"
                         % (NDIRS, v.shape))
    o, t = _id_args(order, tol)
    file = file if isinstance(file, str) else str(file)
    d = fixture_directions()
    return _run(lambda rp: _id_basis(NDIRS, d.ctypes.data, v.shape[1], v.ctypes.data, o, t, rp), "basis", file)


def identify_projection(coeffs, order=None, tol=1e-4, file="FILE"):
    """Name the convention of the user's coefficients of the fixture's light
    (:func:`fixture_light`; sh_identify_projection against shlab's
    coefficients to order 16), as ``shlab identify --projection``.

    coeffs: shape (n,): n² (real), 2n² (complex, re,im) or n(n+1)
    (complex-half) numbers.  order, tol, file: as :func:`identify_basis`.
    The light's coefficients do not tell apart bases that differ only where
    it is zero: then the verdict is ambiguous and needs says so."""
    c = _doubles(coeffs, "coeffs", finite_only=True)
    if c.ndim != 1 or c.shape[0] < 1:
        raise ValueError("coeffs must be one vector (shape (n,)), not shape %s" % (c.shape,))
    o, t = _id_args(order, tol)
    file = file if isinstance(file, str) else str(file)
    ref = fixture_light_coeffs(MAX_ORDER)
    return _run(lambda rp: _id_proj(c.shape[0], c.ctypes.data, ref.ctypes.data, MAX_ORDER, o, t, rp),
                "projection", file)
