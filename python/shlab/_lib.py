"""Loading libshlab.so, the error type, and the checks every call makes.

Where the library is found, first match wins:

1. the environment variable ``SHLAB_LIBRARY`` (a path to ``libshlab.so``);
2. the build tree: ``../../build/libshlab.so`` relative to this package,
   when the package is imported from ``python/`` of a shlab checkout;
3. the library installed beside the package by ``make install``
   (``PREFIX/lib/libshlab.so.0``, recorded in ``_install.py`` at install time);
4. ``libshlab.so.0`` through the system loader (``ctypes.util.find_library``,
   ``ldconfig``'s cache, ``LD_LIBRARY_PATH``).

Every shlab routine returns a status (0 = ``SH_OK``) and keeps a one-line
reason in ``sh_last_error()``; a non-zero status raises :class:`Error`
carrying both.  Arrays are checked here (shape, dtype, contiguity) before any
C call, so the C side never reads or writes outside an array.
"""
import ctypes
import ctypes.util
import os

import numpy as np

__all__ = ["Error", "library_path", "lib"]

# status codes of src/shlab/core.h
SH_OK, SH_EINVAL, SH_ENOMEM, SH_EIO, SH_EFORMAT, SH_ENOTSUP, SH_ENUM = range(7)
STATUS_NAMES = {SH_EINVAL: "SH_EINVAL", SH_ENOMEM: "SH_ENOMEM", SH_EIO: "SH_EIO",
                SH_EFORMAT: "SH_EFORMAT", SH_ENOTSUP: "SH_ENOTSUP", SH_ENUM: "SH_ENUM"}
SHLAB_MAX_ORDER = 4097


class Error(Exception):
    """A shlab routine failed.

    ``message`` is shlab's one-line reason (``sh_last_error()``), ``status``
    the status code it returned (``SH_EINVAL`` = 1, ``SH_ENOMEM`` = 2,
    ``SH_EIO`` = 3, ``SH_EFORMAT`` = 4, ``SH_ENOTSUP`` = 5, ``SH_ENUM`` = 6),
    ``function`` the C function's name.  ``str(err)`` is the message.
    """

    def __init__(self, message, status, function=None):
        super().__init__(message)
        self.message = message
        self.status = status
        self.function = function

    @property
    def status_name(self):
        """The status code's name, e.g. ``"SH_EINVAL"``."""
        return STATUS_NAMES.get(self.status, str(self.status))


def _candidates():
    env = os.environ.get("SHLAB_LIBRARY")
    if env:
        return [env], True
    here = os.path.dirname(os.path.abspath(__file__))
    paths = []
    tree = os.path.normpath(os.path.join(here, "..", "..", "build", "libshlab.so"))
    if os.path.exists(tree):
        paths.append(tree)
    try:
        from . import _install  # written by `make install`
        paths.append(os.path.join(_install.LIBDIR, "libshlab.so.0"))
    except ImportError:
        pass
    found = ctypes.util.find_library("shlab")
    if found:
        paths.append(found)
    paths.append("libshlab.so.0")
    return paths, False


def _load():
    paths, explicit = _candidates()
    errors = []
    for p in paths:
        try:
            return ctypes.CDLL(p), p
        except OSError as e:
            errors.append("%s: %s" % (p, e))
            if explicit:
                break
    raise ImportError("shlab: cannot load libshlab (set SHLAB_LIBRARY to its path, or build it with "
                      "`make`, or `make install`): " + "; ".join(errors))


lib, _path = _load()


def library_path():
    """The path (or name) of the libshlab loaded."""
    return _path


lib.sh_last_error.restype = ctypes.c_char_p
lib.sh_last_error.argtypes = []


def last_error():
    """The reason recorded by the last failing shlab call on this thread."""
    return lib.sh_last_error().decode("utf-8", "replace")


def _errcheck(result, func, args):
    if result != SH_OK:
        raise Error(last_error(), int(result), func.__name__)
    return result


def declare(name, argtypes, restype=ctypes.c_int, status=True):
    """The C function ``name`` with its prototype; calls returning a status
    (``status=True``) raise :class:`Error` when it is not ``SH_OK``.
    A symbol missing from the loaded library gives a stub that raises
    :class:`Error` (``SH_ENOTSUP``) naming the library, when called."""
    try:
        f = getattr(lib, name)
    except AttributeError:
        def missing(*args):
            raise Error("%s is not in the loaded libshlab (%s): the library is older than this package"
                        % (name, _path), SH_ENOTSUP, name)
        missing.missing = True
        return missing
    f.argtypes = argtypes
    f.restype = restype
    if status and restype is ctypes.c_int:
        f.errcheck = _errcheck
    return f


def has(name):
    """True if the loaded library exports ``name``."""
    return hasattr(lib, name)


# ---------------------------------------------------------------- arguments
_sh_check_order = declare("sh_check_order", [ctypes.c_int])


def check_order(order):
    """``order`` as an int, checked by shlab (sh_check_order: 1..4097; a
    shlab.Error with its message otherwise).  A non-integer is a TypeError.
    Routines with a lower limit check it themselves."""
    if isinstance(order, (bool, np.bool_)) or not isinstance(order, (int, np.integer)):
        raise TypeError("order must be an int, not %s" % type(order).__name__)
    if not -2**31 <= int(order) < 2**31:
        raise ValueError("order %d is out of the range of a C int" % order)
    _sh_check_order(int(order))
    return int(order)


def order_of(n, what="coefficients"):
    """The order whose n² coefficients make n (last axis length)."""
    k = int(round(np.sqrt(n)))
    if n < 1 or k * k != n:
        raise ValueError("%s: the last axis has %d entries, not order² for an order n >= 1" % (what, n))
    return k


def real_array(a, dtype, what, writable=False, copy_ok=True):
    """``a`` as a C-contiguous array of ``dtype`` (float64 or float32).

    Integer, bool and float arrays of other widths are converted (a copy);
    complex, object and string arrays are refused (TypeError).  With
    ``copy_ok=False`` the array must already be C-contiguous ``dtype`` (and
    writable if asked), since the caller wants it changed in place."""
    arr = np.asarray(a)
    if arr.dtype.kind not in "fiub":
        raise TypeError("%s must be a real array, not dtype %s" % (what, arr.dtype))
    if not copy_ok:
        if arr.dtype != dtype or not arr.flags.c_contiguous or (writable and not arr.flags.writeable):
            raise TypeError("%s must be a C-contiguous writable %s array to be changed in place (got %s%s)"
                            % (what, np.dtype(dtype).name, arr.dtype,
                               "" if arr.flags.c_contiguous else ", not C-contiguous"))
        return arr
    out = np.asarray(arr, dtype=dtype)
    return out if out.flags.c_contiguous else np.ascontiguousarray(out)


def out_array(out, shape, dtype, what="out"):
    """A new array, or ``out`` checked: exact shape, dtype, C-contiguous, writable."""
    if out is None:
        return np.empty(shape, dtype=dtype)
    if not isinstance(out, np.ndarray):
        raise TypeError("%s must be a numpy array" % what)
    if out.shape != tuple(shape):
        raise ValueError("%s has shape %s, not %s" % (what, out.shape, tuple(shape)))
    if out.dtype != dtype or not out.flags.c_contiguous or not out.flags.writeable:
        raise TypeError("%s must be a C-contiguous writable %s array" % (what, np.dtype(dtype).name))
    return out


def ptr(arr, ctype=ctypes.c_double):
    """A ctypes pointer to the first element of a C-contiguous array."""
    return arr.ctypes.data_as(ctypes.POINTER(ctype))


def cstr(s, what):
    if not isinstance(s, str):
        raise TypeError("%s must be a str, not %s" % (what, type(s).__name__))
    return s.encode("utf-8")


def finite(x, what):
    """A real scalar (float), refusing non-numbers with a TypeError."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise TypeError("%s must be a real number, not %s" % (what, type(x).__name__))
    return float(x)
