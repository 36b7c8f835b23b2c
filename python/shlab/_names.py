"""Names <-> the C enums (conventions, normalisations, methods, ...).

Every name is parsed by shlab's own parser (``sh_*_parse``), so a bad name
raises :class:`shlab.Error` with shlab's message, and the accepted names are
exactly those of the command-line tool.
"""
import ctypes

from ._lib import cstr, declare, lib

_INT_P = ctypes.POINTER(ctypes.c_int)


def _pair(what):
    parse = declare("sh_%s_parse" % what, [ctypes.c_char_p, _INT_P])
    name = declare("sh_%s_name" % what, [ctypes.c_int], ctypes.c_char_p, status=False)

    def to_int(s):
        if isinstance(s, int) and not isinstance(s, bool):
            return s
        v = ctypes.c_int()
        parse(cstr(s, what.replace("_", " ")), ctypes.byref(v))
        return v.value

    def to_name(v):
        r = name(int(v))
        return r.decode() if r else str(v)

    return to_int, to_name


convention, convention_name = _pair("convention")   # "cs", "nocs"
norm, norm_name = _pair("norm")                     # "cs", "nocs", "4pi", "schmidt"
rule, rule_name = _pair("rule")                     # "quad", "mc", "random", "qmc"
precision, precision_name = _pair("precision")      # "double", "float"
method, method_name = _pair("rot_method")           # "zxzxz", "halfpi", ...
kernel, kernel_name = _pair("rot_kernel")           # "auto", "scalar", ...

_layout_parse = declare("sh_layout_parse", [ctypes.c_char_p, _INT_P])


def layout(s):
    """"latlong" or "probe" (angle-map light probe) as sh_layout."""
    v = ctypes.c_int()
    _layout_parse(cstr(s, "layout"), ctypes.byref(v))
    return v.value


SH_ROT_AUTO = -1


def method_or_auto(s):
    """A rotation method name, or "auto" (SH_ROT_AUTO: zxzxz up to order 32, halfpi above)."""
    if s == "auto":
        return SH_ROT_AUTO
    return method(s)


def method_or_auto_name(v):
    return "auto" if v == SH_ROT_AUTO else method_name(v)


__all__ = ["convention", "convention_name", "norm", "norm_name", "rule", "rule_name", "precision",
           "precision_name", "method", "method_name", "kernel", "kernel_name", "layout", "lib"]
