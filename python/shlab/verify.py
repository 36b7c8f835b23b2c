"""Golden rotation fixtures and the verdict on a kernel (src/shlab/verify.h):
the library side of ``shlab verify``, so a Python kernel gets the same
verdict and the same diagnosis text as the command-line tool.

- :func:`load_fixture` reads a fixture file (data/fixtures/rotation/*.json);
  each case's arrays are read-only numpy views of the C fixture (no copy).
- :func:`verify` judges a kernel — a Python callable or a dict of outputs —
  and, when it fails, names the likely mistake (sh_verify_judge,
  sh_verify_diagnose).
- :func:`simulate` gives what a kernel with a known mistake outputs
  (sh_fixture_simulate), :func:`load_candidate` reads a candidate file,
  :func:`apply_method` runs one of shlab's own methods on every case.
"""
import ctypes
import math
import os

import numpy as np

from . import _names
from ._lib import cstr, declare
from .rotation import CRotation, Rotation

__all__ = ["load_fixture", "verify", "simulate", "load_candidate", "apply_method", "mistakes",
           "mistake_description", "Fixture", "Case", "VerifyResult"]

_P = ctypes.c_void_p
_DP = ctypes.POINTER(ctypes.c_double)


class CFixtureCase(ctypes.Structure):
    """ctypes mirror of sh_fixture_case (src/shlab/verify.h)."""
    _fields_ = [("id", ctypes.c_char * 64), ("order", ctypes.c_int), ("band", ctypes.c_int),
                ("conv", ctypes.c_int), ("rot", CRotation), ("n", ctypes.c_int), ("input", _DP),
                ("expected", _DP), ("expected_f", _DP), ("tol_double", ctypes.c_double),
                ("tol_float", ctypes.c_double)]


class CFixture(ctypes.Structure):
    """ctypes mirror of sh_fixture."""
    _fields_ = [("ncases", ctypes.c_int), ("cases", ctypes.POINTER(CFixtureCase))]


class CVerdict(ctypes.Structure):
    """ctypes mirror of sh_verdict."""
    _fields_ = [("cases", ctypes.c_int), ("run", ctypes.c_int), ("failed", ctypes.c_int),
                ("failed_near", ctypes.c_int), ("worst_case", ctypes.c_int), ("worst_index", ctypes.c_int),
                ("worst_error", ctypes.c_double), ("worst_tolerance", ctypes.c_double)]


class CDiagnosis(ctypes.Structure):
    """ctypes mirror of sh_diagnosis."""
    _fields_ = [("found", ctypes.c_int), ("float_only", ctypes.c_int), ("mistake", ctypes.c_int),
                ("cause", ctypes.c_char_p), ("matches", ctypes.c_int), ("checked", ctypes.c_int)]


_DIAG_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_long, ctypes.c_long)
_FXP = ctypes.POINTER(CFixture)
_CP = ctypes.POINTER(CFixtureCase)
_load = declare("sh_fixture_load", [ctypes.c_char_p, _FXP])
_free = declare("sh_fixture_free", [_FXP], None, status=False)
_load_cand = declare("sh_fixture_load_candidate", [ctypes.c_char_p, _FXP, _P, ctypes.POINTER(_DP), _P])
_apply = declare("sh_fixture_apply", [ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int, _CP,
                                      ctypes.POINTER(CRotation), ctypes.c_int, _P, _P])
_m_name = declare("sh_mistake_name", [ctypes.c_int], ctypes.c_char_p, status=False)
_m_desc = declare("sh_mistake_description", [ctypes.c_int], ctypes.c_char_p, status=False)
_m_parse = declare("sh_mistake_parse", [ctypes.c_char_p, ctypes.POINTER(ctypes.c_int)])
_simulate = declare("sh_fixture_simulate", [ctypes.c_int, _CP, _P])
_judge = declare("sh_verify_judge", [_FXP, _P, ctypes.POINTER(_DP), ctypes.c_int, ctypes.POINTER(CVerdict)])
_diagnose = declare("sh_verify_diagnose", [_FXP, _P, ctypes.POINTER(_DP), ctypes.c_int, _DIAG_PROGRESS, _P,
                                           ctypes.POINTER(CDiagnosis)])
MISTAKE_COUNT = 9  # SH_MISTAKE_COUNT


def available():
    """True if the loaded libshlab has the fixture and verdict API (verify.h)."""
    return not getattr(_load, "missing", False)


def mistakes():
    """The names of the known mistakes ("convention", "inverse", "swap", ...)."""
    return [_m_name(t).decode() for t in range(MISTAKE_COUNT)]


def _mistake(m):
    v = ctypes.c_int()
    _m_parse(cstr(m, "mistake"), ctypes.byref(v))
    return v.value


def mistake_description(m):
    """The one-line description a diagnosis prints for mistake ``m`` (a name)."""
    return _m_desc(_mistake(m)).decode()


class _View:
    """Exposes n doubles at addr as an array whose base keeps `owner` alive."""

    def __init__(self, owner, addr, n):
        self._owner = owner
        self.__array_interface__ = {"shape": (n,), "typestr": "<f8", "data": (addr, True), "version": 3}


def _view(owner, p, n):
    return np.asarray(_View(owner, ctypes.cast(p, _P).value, n))


class Case:
    """One golden case: rotate ``input`` by ``rotation`` in ``convention``.

    id, order, band (-1: all bands 0..order-1; else the one band, with
    n = 2·band+1 coefficients), convention ("cs"/"nocs"), rotation
    (shlab.Rotation), matrix (3×3), euler (α, β, γ), n, input, expected
    (exact to double rounding), expected_f (rounded to float32), tol_double,
    tol_float.  The arrays are read-only views of the loaded fixture."""

    def __init__(self, fixture, index, c):
        self.fixture, self.index, self._c = fixture, index, c
        self.id = c.id.decode()
        self.order, self.band, self.n = c.order, c.band, c.n
        self.convention = _names.convention_name(c.conv)
        self.rotation = Rotation(CRotation.from_buffer_copy(c.rot))
        self.matrix = self.rotation.matrix
        self.euler = self.rotation.euler
        self.input = _view(fixture, c.input, c.n)
        self.expected = _view(fixture, c.expected, c.n)
        self.expected_f = _view(fixture, c.expected_f, c.n)
        self.tol_double, self.tol_float = c.tol_double, c.tol_float

    @property
    def band_slice(self):
        """Where the case's coefficients sit in a full vector of its order."""
        if self.band < 0:
            return slice(0, self.n)
        return slice(self.band * self.band, (self.band + 1) * (self.band + 1))

    def __repr__(self):
        return "<Case %s order %d band %d %s>" % (self.id, self.order, self.band, self.convention)


class Fixture:
    """A loaded fixture file: ``cases`` (list of :class:`Case`), indexable by
    position or case id; ``path``."""

    def __init__(self, path):
        self.path = os.fspath(path)
        self._c = CFixture()
        self._loaded = False
        _load(cstr(self.path, "path"), ctypes.byref(self._c))
        self._loaded = True
        self.cases = [Case(self, k, self._c.cases[k]) for k in range(self._c.ncases)]
        self._by_id = {c.id: c for c in self.cases}

    def __del__(self):
        if getattr(self, "_loaded", False):
            _free(ctypes.byref(self._c))
            self._loaded = False

    def __len__(self):
        return len(self.cases)

    def __iter__(self):
        return iter(self.cases)

    def __getitem__(self, key):
        return self._by_id[key] if isinstance(key, str) else self.cases[key]

    def __contains__(self, key):
        return key in self._by_id


def load_fixture(path):
    """Read a fixture file (format "shlab-rotation-fixtures/1"; shlab.Error
    with shlab's message if it is missing or malformed)."""
    return Fixture(path)


def _fixture(fx):
    return fx if isinstance(fx, Fixture) else load_fixture(fx)


def simulate(case, mistake):
    """What a kernel with ``mistake`` (a name from :func:`mistakes`) outputs
    for ``case`` (exact method, double): an array of case.n values."""
    out = np.empty(case.n)
    _simulate(_mistake(mistake), ctypes.byref(case._c), out.ctypes.data)
    return out


def load_candidate(fixture, path):
    """A candidate file {"results": {"<case id>": [n numbers], ...}} as a
    dict {case id: array} (every case of the fixture must be there)."""
    fx = _fixture(fixture)
    outs = [np.empty(c.n) for c in fx.cases]
    ptrs = (_DP * max(1, len(outs)))(*[o.ctypes.data_as(_DP) for o in outs])
    _load_cand(cstr(os.fspath(path), "path"), ctypes.byref(fx._c), None, ptrs, None)
    return {c.id: o for c, o in zip(fx.cases, outs)}


def apply_method(fixture, method, precision="double", kernel="auto", matrix_input=False):
    """Outputs of shlab's rotation ``method`` on every case within its order
    (sh_fixture_apply), as {case id: array}."""
    from .rotate import method_max_order
    fx = _fixture(fixture)
    m, p, k = _names.method(method), _names.precision(precision), _names.kernel(kernel)
    top = method_max_order(method)
    res = {}
    for c in fx.cases:
        if c.order > top:
            continue
        out = np.empty(c.n)
        _apply(m, p, k, 1 if matrix_input else 0, ctypes.byref(c._c), ctypes.byref(c._c.rot), c._c.conv,
               c.input.ctypes.data, out.ctypes.data)
        res[c.id] = out
    return res


class VerifyResult:
    """The verdict, with the fields of ``shlab verify --format json``:
    fixture, source, tolerance_kind, cases, failed, pass (also ``passed``),
    worst_id, worst_index, worst_got, worst_expected, worst_error,
    worst_tolerance, convention, skipped (when non-zero), and after a failure
    with diagnose: diagnosis, diagnosis_matches, diagnosis_checked,
    diagnosis_tolerance.  Read them as attributes or ``result["key"]``;
    ``as_dict()`` gives the JSON object (non-finite numbers as "not finite",
    as the CLI prints them).  Also: run (cases judged), failed_near (failed
    cases within their float32 tolerance), mistake (the diagnosed mistake's
    name, or None)."""

    def __init__(self, fields):
        self._fields = fields
        for k, v in fields.items():
            setattr(self, k, v)
        self.passed = fields["pass"]

    def __getitem__(self, key):
        return self._fields[key]

    def __contains__(self, key):
        return key in self._fields

    def as_dict(self):
        return {k: v for k, v in self._fields.items() if k not in ("run", "failed_near", "mistake")}

    def __repr__(self):
        return "VerifyResult(%r)" % self.as_dict()


def _outputs_from_callable(fx, kernel):
    got, skip = [], []
    for c in fx.cases:
        full_n = c.order * c.order
        x = np.zeros(full_n)
        sl = c.band_slice
        x[sl] = c.input
        y = kernel(c.order, c.matrix.copy(), x, c.convention)
        if y is None:
            got.append(None)
            skip.append(1)
            continue
        y = np.asarray(y)
        if y.dtype.kind not in "fiu":
            raise TypeError("kernel returned dtype %s for case %s; a real array is needed" % (y.dtype, c.id))
        if y.shape != (full_n,):
            raise ValueError("kernel returned shape %s for case %s (order %d): %d values needed"
                             % (y.shape, c.id, c.order, full_n))
        got.append(np.ascontiguousarray(y[sl], dtype=np.float64))
        skip.append(0)
    return got, skip


def _outputs_from_dict(fx, outputs):
    unknown = [k for k in outputs if k not in fx]
    if unknown:
        raise ValueError("outputs for case ids not in the fixture: %s" % ", ".join(map(str, unknown[:5])))
    got, skip = [], []
    for c in fx.cases:
        if c.id not in outputs or outputs[c.id] is None:
            got.append(None)
            skip.append(1)
            continue
        y = np.asarray(outputs[c.id])
        if y.dtype.kind not in "fiu":
            raise TypeError("output of case %s has dtype %s; a real array is needed" % (c.id, y.dtype))
        if y.shape != (c.n,):
            raise ValueError("output of case %s has shape %s, not (%d,)" % (c.id, y.shape, c.n))
        got.append(np.ascontiguousarray(y, dtype=np.float64))
        skip.append(0)
    return got, skip


def _num(x):
    return x if math.isfinite(x) else "not finite"


def verify(fixture, kernel_or_outputs, precision="double", diagnose=True, source=None):
    """Judge a rotation kernel against a fixture, as ``shlab verify`` does.

    fixture: a :class:`Fixture` or a path.  kernel_or_outputs:

    - a callable ``f(order, R, input, convention) -> ndarray``: R the case's
      3×3 rotation matrix (row-major, active: g(s) = f(R⁻¹ s)), input the
      order² coefficients (float64), convention "cs" or "nocs"; it returns
      the order² rotated coefficients.  For a one-band case (band >= 0) the
      callable gets the full vector of order band+1 with zeros outside the
      band, and only the band's 2·band+1 outputs are judged.  Returning None
      skips the case (a kernel that does not handle it);
    - or a dict {case id: array of case.n outputs}; cases absent are skipped.

    precision: "double" judges at each case's tol_double, "float" at its
    tol_float.  With diagnose (default), a failure is explained by the known
    mistakes (sh_verify_diagnose), giving the same diagnosis text as
    ``shlab verify --diagnose``.  Returns a :class:`VerifyResult`."""
    fx = _fixture(fixture)
    prec = _names.precision(precision)
    if callable(kernel_or_outputs):
        got, skip = _outputs_from_callable(fx, kernel_or_outputs)
        src = source or getattr(kernel_or_outputs, "__name__", "python")
    elif isinstance(kernel_or_outputs, dict):
        got, skip = _outputs_from_dict(fx, kernel_or_outputs)
        src = source or "python"
    else:
        raise TypeError("kernel_or_outputs must be a callable or a dict {case id: array}")
    if all(skip):
        raise ValueError("no case of the fixture was run (every case skipped)")
    got = [g if g is not None else np.zeros(c.n) for g, c in zip(got, fx.cases)]
    ptrs = (_DP * len(got))(*[g.ctypes.data_as(_DP) for g in got])
    skipb = np.array(skip, dtype=np.uint8)
    v = CVerdict()
    _judge(ctypes.byref(fx._c), skipb.ctypes.data, ptrs, prec, ctypes.byref(v))
    wc = fx.cases[v.worst_case]
    wg = float(got[v.worst_case][v.worst_index])
    convs = {c.convention for c in fx.cases}
    fields = {
        "fixture": fx.path, "source": src, "tolerance_kind": "float32" if prec == 1 else "double",
        "cases": v.cases, "failed": v.failed, "pass": v.failed == 0, "worst_id": wc.id,
        "worst_index": v.worst_index, "worst_got": _num(wg), "worst_expected": float(wc.expected[v.worst_index]),
        "worst_error": _num(v.worst_error), "worst_tolerance": v.worst_tolerance,
        "convention": "cs+nocs" if len(convs) > 1 else convs.pop(),
        "run": v.run, "failed_near": v.failed_near, "mistake": None,
    }
    if int(skipb.sum()):
        fields["skipped"] = int(skipb.sum())
    if diagnose and v.failed:
        d = CDiagnosis()
        _diagnose(ctypes.byref(fx._c), skipb.ctypes.data, ptrs, prec, _DIAG_PROGRESS(), None, ctypes.byref(d))
        fields["diagnosis"] = d.cause.decode()
        fields["diagnosis_matches"] = d.matches
        fields["diagnosis_checked"] = d.checked
        fields["diagnosis_tolerance"] = "float32"
        if d.found and not d.float_only:
            fields["mistake"] = _m_name(d.mistake).decode()
    return VerifyResult(fields)
