"""Conversions keep the represented function: checked with the closed-form
bases in numpy (4π: y' = sqrt(4π) y_nocs; Schmidt: y' = sqrt(4π/(2l+1)) y_nocs)."""
import numpy as np
import pytest

import shlab
from shtruth import ODD_M, PI, band_of, random_dirs, sh_closed


def basis(norm, d):
    y = sh_closed(d, "nocs")
    l = band_of(16)
    if norm == "cs":
        return sh_closed(d, "cs")
    if norm == "nocs":
        return y
    if norm == "4pi":
        return y * np.sqrt(4 * PI)
    return y * np.sqrt(4 * PI / (2 * l + 1))


@pytest.mark.parametrize("src", ["cs", "nocs", "4pi", "schmidt"])
@pytest.mark.parametrize("dst", ["cs", "nocs", "4pi", "schmidt"])
def test_convert_keeps_the_function(src, dst):
    c = np.random.default_rng(5).normal(size=16)
    d = random_dirs(50, 6)
    c2 = shlab.convert(c, src, dst)
    np.testing.assert_allclose(basis(dst, d) @ c2, basis(src, d) @ c, atol=1e-13)
    np.testing.assert_allclose(shlab.convert(c2, dst, src), c, rtol=1e-14, atol=1e-15)


def test_convention_switch_negates_odd_m():
    c = np.arange(1.0, 17.0)
    np.testing.assert_array_equal(shlab.convention_switch(c), np.where(ODD_M, -c, c))
    np.testing.assert_array_equal(shlab.convention_switch(np.stack([c, 2 * c]))[1], 2 * np.where(ODD_M, -c, c))


def test_inplace_and_refusals():
    c = np.random.default_rng(1).normal(size=(3, 9))
    orig = c.copy()
    assert shlab.convert_inplace(c, "cs", "4pi") is c
    np.testing.assert_allclose(c, shlab.convert(orig, "cs", "4pi"), rtol=0, atol=0)
    with pytest.raises(TypeError, match="in place"):
        shlab.convert_inplace(np.zeros((9, 3)).T, "cs", "nocs")  # not C-contiguous
    with pytest.raises(TypeError, match="in place"):
        shlab.convert_inplace(np.zeros(9, dtype=np.float32), "cs", "nocs")
    with pytest.raises(ValueError, match="order²"):
        shlab.convert(np.zeros(8), "cs", "nocs")
    with pytest.raises(shlab.Error) as e:
        shlab.convert(np.zeros(4), "cs", "orthonormal")
    assert e.value.status == 1
    # a non-contiguous input is converted (a copy) and the input left alone
    a = np.arange(18.0).reshape(9, 2)
    out = shlab.convert(a[:, 0], "cs", "nocs")
    np.testing.assert_array_equal(out, np.where(ODD_M[:9], -a[:, 0], a[:, 0]))
    assert a[1, 0] == 2.0
