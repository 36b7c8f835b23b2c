"""Projection against numerical quadrature in numpy: zonal closed forms by
Gauss-Legendre on the lit part, a band-limited polynomial projected exactly,
Green's light by dense quadrature, lat-long images of a known function."""
import os

import numpy as np
import pytest

import shlab
from shtruth import PI, quad_nodes, sh_closed


def zonal_by_quadrature(f, a, order, n=64):
    """2π ∫_a^1 f(x) Y_l0(x) dx by Gauss-Legendre on [a, 1] (Y_l0 = sqrt((2l+1)/4π) P_l)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x = a + (1 - a) * (x + 1) / 2
    w = w * (1 - a) / 2
    z = []
    for l in range(order):
        P = np.polynomial.legendre.Legendre.basis(l)(x)
        z.append(2 * PI * np.sum(w * f(x) * np.sqrt((2 * l + 1) / (4 * PI)) * P))
    return np.array(z)


def test_cap_closed_form_by_quadrature():
    t, order = 0.7, 12
    z = zonal_by_quadrature(lambda x: np.ones_like(x), np.cos(t), order)
    np.testing.assert_allclose(shlab.cap_zonal(t, order), z, atol=1e-14)
    c = shlab.Light.cap(t).closed_form(order)
    np.testing.assert_allclose(c[[l * (l + 1) for l in range(order)]], z, atol=1e-14)
    assert np.count_nonzero(c) == order  # zonal


def test_lobe_closed_form_by_quadrature():
    e, order = 3.0, 10
    z = zonal_by_quadrature(lambda x: x ** e, 0.0, order)
    np.testing.assert_allclose(shlab.lobe_zonal(e, order), z, atol=1e-14)
    assert shlab.Light.lobe(e).has_closed_form and not shlab.Light.green().has_closed_form


def test_const_light_every_rule():
    for rule in ("quad", "mc", "random", "qmc"):
        c = shlab.project_light("const:2", 2, rule=rule, samples=400, seed=3)
        # ∫ 2 y_0^0 dΩ = 2·sqrt(4π); the Monte Carlo rules weigh each point 4π/N
        assert c[0] == pytest.approx(2 * np.sqrt(4 * PI), rel=1e-12)


def test_polynomial_function_projected_exactly():
    # f = x·y + z = (2/sqrt(15/π)) y_2^{-2} + sqrt(4π/3) y_1^0 (cs)
    c = shlab.project_function(lambda d, th, ph: d[0] * d[1] + d[2], 4, samples=6)
    want = np.zeros(16)
    want[4] = 2 / np.sqrt(15 / PI)
    want[2] = np.sqrt(4 * PI / 3)
    np.testing.assert_allclose(c, want, atol=1e-14)


def test_green_light_against_numpy_quadrature():
    def green(d):  # Green (2003) Fig. 7, the reading with the −3 inside the second max
        th = np.arccos(np.clip(d[:, 2], -1, 1))
        ph = np.arctan2(d[:, 1], d[:, 0])
        return np.maximum(0, 5 * np.cos(th) - 4) + np.maximum(0, -4 * np.sin(th - PI) * np.cos(ph - 2.5) - 3)
    L = shlab.Light.green()
    d, w = quad_nodes(400)
    np.testing.assert_allclose(L(d[:50]), green(d[:50]), atol=1e-14)
    truth = (w * green(d)) @ sh_closed(d)
    np.testing.assert_allclose(shlab.green_reference(4), truth, atol=2e-5)
    np.testing.assert_allclose(shlab.project_light(L, 4, samples=300), truth, atol=5e-5)


def latlong_of(f, W, H):
    th = PI * (np.arange(H) + 0.5) / H
    ph = 2 * PI * (np.arange(W) + 0.5) / W
    T, P = np.meshgrid(th, ph, indexing="ij")
    d = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1)
    return f(d), d


def test_image_projection_of_a_known_function(tmp_path):
    W, H = 256, 128
    f = lambda d: 1.0 + d[..., 2] + 0.5 * d[..., 0] * d[..., 1]  # noqa: E731
    img, d = latlong_of(f, W, H)
    # the numpy truth: exact coefficients of f (closed forms, cs)
    want = np.zeros(9)
    want[0] = np.sqrt(4 * PI)
    want[2] = np.sqrt(4 * PI / 3)
    want[4] = 0.5 * 2 / np.sqrt(15 / PI)
    c = shlab.project_image(img, 3)
    assert c.shape == (9,)
    np.testing.assert_allclose(c, want, atol=2e-4)
    # pixel solid angles against the exact Δφ·(cos θ_top − cos θ_bottom)
    edges = np.cos(PI * np.arange(H + 1) / H)
    om = np.repeat(((edges[:-1] - edges[1:]) * 2 * PI / W)[:, None], W, axis=1)
    np.testing.assert_allclose(shlab.pixel_solid_angles("latlong", W, H), om, rtol=1e-12)
    # three channels, interleaved (a copy) or channel-first views (none): the same numbers
    rgb = np.stack([img, 2 * img, -img], axis=-1).astype(np.float32)
    c3 = shlab.project_image(rgb, 3)
    assert c3.shape == (3, 9)
    np.testing.assert_allclose(c3[1], 2 * c3[0], rtol=1e-6)
    planar = np.ascontiguousarray(np.moveaxis(rgb, 2, 0))
    np.testing.assert_array_equal(shlab.project_image(np.moveaxis(planar, 0, 2), 3), c3)
    # through an EXR file
    p = os.path.join(str(tmp_path), "env.exr")
    shlab.write_exr(p, rgb)
    back, names = shlab.read_exr(p)
    assert names == ["R", "G", "B"] and back.shape == (H, W, 3)
    np.testing.assert_array_equal(back, rgb)
    np.testing.assert_array_equal(shlab.project_exr(p, 3), c3)


def test_projection_errors(tmp_path):
    with pytest.raises(shlab.Error, match="carries orders up to") as e:
        shlab.project_image(np.ones((8, 16)), 40)
    assert e.value.status == 1
    assert shlab.image_max_order(np.ones((8, 16))) < 40
    with pytest.raises(shlab.Error) as e:
        shlab.project_exr(os.path.join(str(tmp_path), "missing.exr"), 2)
    assert e.value.status == 3  # SH_EIO
    bad = os.path.join(str(tmp_path), "bad.exr")
    with open(bad, "wb") as fh:
        fh.write(b"not an exr at all")
    with pytest.raises(shlab.Error):
        shlab.read_exr(bad)
    with pytest.raises(ValueError, match="shape"):
        shlab.project_image(np.ones((4, 8, 5)), 2)
    with pytest.raises(TypeError):
        shlab.project_image(np.ones((4, 8), dtype=complex), 2)
    with pytest.raises(shlab.Error, match="cap"):
        shlab.Light("cap")
    with pytest.raises(shlab.Error) as e:
        shlab.Light.green().closed_form(3)
    assert e.value.status == 5  # SH_ENOTSUP
    with pytest.raises(ZeroDivisionError):
        shlab.project_function(lambda d, th, ph: 1 / 0, 2)
