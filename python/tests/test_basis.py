"""Evaluation against closed forms written here in numpy, orthonormality by
numpy's Gauss-Legendre quadrature, and the argument checks."""
import numpy as np
import pytest

import shlab
from shtruth import PI, quad_nodes, random_dirs, sh_closed


@pytest.mark.parametrize("conv", ["cs", "nocs"])
def test_eval_dir_matches_closed_forms(conv):
    d = random_dirs(200, 1)
    got = shlab.eval_dir(4, d, conv)
    assert got.shape == (200, 16)
    np.testing.assert_allclose(got, sh_closed(d, conv), rtol=0, atol=2e-15)


def test_cs_p_functions_signs():
    # docs/CONVENTIONS.md: with cs, y_1^{-1} = -sqrt(3/(4π)) y, y_1^0 = +.. z, y_1^1 = -.. x
    k = np.sqrt(3 / (4 * PI))
    d = np.array([0.48, -0.6, 0.64])
    y = shlab.eval_dir(2, d)
    np.testing.assert_allclose(y[1:4], [-k * d[1], k * d[2], -k * d[0]], rtol=1e-15, atol=0)
    y = shlab.eval_dir(2, d, "nocs")
    np.testing.assert_allclose(y[1:4], [k * d[1], k * d[2], k * d[0]], rtol=1e-15, atol=0)


def test_eval_angles_broadcasts_and_matches_dirs():
    th = np.linspace(0, PI, 7)[:, None]
    ph = np.linspace(0, 2 * PI, 5)[None, :]
    got = shlab.eval_angles(4, th, ph)
    assert got.shape == (7, 5, 16)
    d = np.stack(np.broadcast_arrays(np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)), axis=-1)
    np.testing.assert_allclose(got, sh_closed(d), atol=3e-15)
    assert shlab.eval_angles(3, 0.2, 0.1).shape == (9,)


def test_orthonormal_by_numpy_quadrature():
    order = 12
    d, w = quad_nodes(order + 1)
    Y = shlab.eval_dir(order, d)
    G = Y.T @ (w[:, None] * Y)
    np.testing.assert_allclose(G, np.eye(order * order), atol=1e-13)


def test_out_argument_is_filled_without_copy():
    out = np.zeros((3, 9))
    res = shlab.eval_dir(3, random_dirs(3, 2), out=out)
    assert res is out and np.all(out[:, 0] != 0)
    with pytest.raises(ValueError):
        shlab.eval_dir(3, random_dirs(3, 2), out=np.zeros((3, 4)))
    with pytest.raises(TypeError):
        shlab.eval_dir(3, random_dirs(3, 2), out=np.zeros((3, 9), dtype=np.float32))


def test_errors():
    with pytest.raises(shlab.Error) as e:
        shlab.eval_angles(0, 0.1, 0.2)
    assert e.value.status == 1 and "order 0" in str(e.value) and e.value.status_name == "SH_EINVAL"
    with pytest.raises(shlab.Error, match="4097"):
        shlab.eval_dir(5000, [0, 0, 1])
    with pytest.raises(shlab.Error, match="zero length"):
        shlab.eval_dir(2, [0.0, 0.0, 0.0])
    with pytest.raises(shlab.Error):
        shlab.eval_dir(2, [np.nan, 0.0, 1.0])
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        shlab.eval_dir(2, np.ones((4, 2)))
    with pytest.raises(TypeError, match="real array"):
        shlab.eval_dir(2, np.ones(3, dtype=complex))
    with pytest.raises(TypeError):
        shlab.eval_angles(2.5, 0.1, 0.1)
    with pytest.raises(shlab.Error, match="convention"):
        shlab.eval_angles(2, 0.1, 0.1, convention="condon")


def test_angles_round_trip():
    d = random_dirs(20, 3)
    th, ph = shlab.angles_from_dir(d)
    assert np.all((th >= 0) & (th <= PI) & (ph >= 0) & (ph < 2 * PI))
    np.testing.assert_allclose(shlab.dir_from_angles(th, ph), d, atol=1e-15)
