"""Independent truths for the tests, in numpy only: closed forms of the real
SH of bands 0..3 in Cartesian coordinates (docs/CONVENTIONS.md: cs has the
Condon-Shortley phase, y_1^{-1} ∝ -y, y_1^0 ∝ z, y_1^1 ∝ -x; nocs negates
odd m), and Gauss-Legendre × uniform-φ quadrature."""
import numpy as np

PI = np.pi


def sh_closed_nocs(d):
    """Real SH of bands 0..3, nocs (no Condon-Shortley phase), at unit
    vectors d (..., 3): shape (..., 16), index l(l+1)+m."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    c = [
        0.5 * np.sqrt(1 / PI) * np.ones_like(x),
        np.sqrt(3 / (4 * PI)) * y, np.sqrt(3 / (4 * PI)) * z, np.sqrt(3 / (4 * PI)) * x,
        0.5 * np.sqrt(15 / PI) * x * y, 0.5 * np.sqrt(15 / PI) * y * z,
        0.25 * np.sqrt(5 / PI) * (3 * z * z - 1),
        0.5 * np.sqrt(15 / PI) * x * z, 0.25 * np.sqrt(15 / PI) * (x * x - y * y),
        0.25 * np.sqrt(35 / (2 * PI)) * y * (3 * x * x - y * y), 0.5 * np.sqrt(105 / PI) * x * y * z,
        0.25 * np.sqrt(21 / (2 * PI)) * y * (5 * z * z - 1), 0.25 * np.sqrt(7 / PI) * z * (5 * z * z - 3),
        0.25 * np.sqrt(21 / (2 * PI)) * x * (5 * z * z - 1), 0.25 * np.sqrt(105 / PI) * z * (x * x - y * y),
        0.25 * np.sqrt(35 / (2 * PI)) * x * (x * x - 3 * y * y),
    ]
    return np.stack(c, axis=-1)


ODD_M = np.array([m % 2 != 0 for l in range(4) for m in range(-l, l + 1)])


def sh_closed(d, convention="cs"):
    y = sh_closed_nocs(d)
    if convention == "cs":
        y = y * np.where(ODD_M, -1.0, 1.0)
    return y


def band_of(n2):
    return np.array([l for l in range(int(np.sqrt(n2))) for _ in range(2 * l + 1)])


def quad_nodes(nt, nphi=None):
    """Gauss-Legendre in cosθ × uniform φ: (unit vectors (N, 3), weights (N,)),
    exact for band-limited functions of total band < 2·nt when nphi > total band."""
    nphi = nphi or 2 * nt
    x, w = np.polynomial.legendre.leggauss(nt)
    phi = 2 * PI * (np.arange(nphi) + 0.5) / nphi
    X, P = np.meshgrid(x, phi, indexing="ij")
    W = np.repeat(w[:, None], nphi, axis=1) * (2 * PI / nphi)
    s = np.sqrt(1 - X * X)
    d = np.stack([s * np.cos(P), s * np.sin(P), X], axis=-1).reshape(-1, 3)
    return d, W.ravel()


def random_dirs(n, seed):
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def random_rotation(seed):
    """A random proper rotation by numpy's QR."""
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def rz(a):
    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])


def ry(b):
    return np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
