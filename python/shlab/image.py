"""Environment images: numpy arrays <-> shlab's sh_image, and OpenEXR reading.

An image is a numpy array of shape (H, W) (one channel) or (H, W, C) with
C = 1..4 channels (Y, or R, G, B[, A]).  shlab stores images planar (channel,
row, column) in float32: an array whose channel-first view
``np.moveaxis(img, -1, 0)`` is C-contiguous float32 — as :func:`read_exr`
returns — is handed to C without a copy; any other is converted with
np.ascontiguousarray (one float32 copy).
"""
import ctypes
import os

import numpy as np

from ._lib import cstr, declare, real_array

__all__ = ["read_exr", "write_exr", "pixel_solid_angles"]

MAX_CHANNELS = 4


class CImage(ctypes.Structure):
    """ctypes mirror of sh_image (src/shlab/io.h)."""
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("nchan", ctypes.c_int),
                ("names", (ctypes.c_char * 8) * MAX_CHANNELS), ("data", ctypes.POINTER(ctypes.c_float))]


_IP = ctypes.POINTER(CImage)
_exr_read = declare("sh_exr_read", [ctypes.c_char_p, _IP, ctypes.POINTER(ctypes.c_int)])
_image_free = declare("sh_image_free", [_IP], None, status=False)
_solid = declare("sh_pixel_solid_angles", [ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_void_p])

_DEFAULT_NAMES = {1: ["Y"], 2: ["R", "G"], 3: ["R", "G", "B"], 4: ["R", "G", "B", "A"]}


def planar(img):
    """(planar float32 C-contiguous array (C, H, W), single-channel input?) of
    an image array (H, W) or (H, W, C)."""
    a = np.asarray(img)
    if a.dtype.kind not in "fiu":
        raise TypeError("image must be a real array, not dtype %s" % a.dtype)
    if a.ndim == 2:
        p, flat = a[np.newaxis], True
    elif a.ndim == 3 and 1 <= a.shape[2] <= MAX_CHANNELS:
        p, flat = np.moveaxis(a, 2, 0), False
    else:
        raise ValueError("image must have shape (H, W) or (H, W, C) with 1 <= C <= 4, not %s" % (a.shape,))
    if p.shape[1] < 1 or p.shape[2] < 1:
        raise ValueError("image has no pixels (shape %s)" % (a.shape,))
    if p.shape[1] * p.shape[2] >= 2 ** 31:
        raise ValueError("image of %d × %d pixels is beyond a C int" % (p.shape[2], p.shape[1]))
    return np.ascontiguousarray(p, dtype=np.float32), flat


def c_image(p, names=None):
    """An sh_image over the planar float32 array p (C, H, W) (no copy: keep p alive)."""
    c = CImage()
    c.nchan, c.height, c.width = p.shape
    for k, nm in enumerate(names or _DEFAULT_NAMES[p.shape[0]]):
        c.names[k].value = nm.encode()[:7]
    c.data = p.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
    return c


def read_exr(path):
    """Read an OpenEXR image (any compression, DWAA/DWAB included).

    Returns (pixels, channels): pixels of shape (H, W, C) float32, a view of a
    planar (C, H, W) array (so projecting it needs no copy); channels the
    names ("R", "G", "B" or "Y").  A missing or unreadable file raises
    shlab.Error (SH_EIO), a corrupt one SH_EFORMAT, with shlab's message."""
    c = CImage()
    fb = ctypes.c_int()
    _exr_read(cstr(os.fspath(path), "path"), ctypes.byref(c), ctypes.byref(fb))
    try:
        nc, h, w = c.nchan, c.height, c.width
        n = nc * h * w
        flat = np.ctypeslib.as_array(c.data, shape=(n,)).copy()
        names = [c.names[k].value.decode() for k in range(c.nchan)]
    finally:
        _image_free(ctypes.byref(c))
    return np.moveaxis(flat.reshape(nc, h, w), 0, 2), names


def pixel_solid_angles(layout, width, height):
    """The exact solid angle of every pixel, shape (height, width) (sh_pixel_solid_angles)."""
    from . import _names
    for v, w in ((width, "width"), (height, "height")):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not 1 <= v < 2 ** 31:
            raise ValueError("%s must be a positive int, not %r" % (w, v))
    if int(width) * int(height) > (1 << 26):
        raise ValueError("%d × %d pixels is more than shlab's largest image (2^26 pixels)" % (width, height))
    out = np.empty((int(height), int(width)))
    _solid(_names.layout(layout), int(width), int(height), out.ctypes.data)
    return out


_exr_write = declare("sh_exr_write", [ctypes.c_char_p, _IP])


def write_exr(path, image, channels=None):
    """Write an image array ((H, W) or (H, W, C)) as a float EXR (sh_exr_write:
    written to a temporary name and renamed).  channels: names (default Y,
    or R, G, B[, A])."""
    p, _ = planar(image)
    if channels is not None and len(channels) != p.shape[0]:
        raise ValueError("%d channel names for %d channels" % (len(channels), p.shape[0]))
    c = c_image(p, list(channels) if channels else None)
    _exr_write(cstr(os.fspath(path), "path"), ctypes.byref(c))
