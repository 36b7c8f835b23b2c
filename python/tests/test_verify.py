"""Fixtures and the verdict (verify.h) from Python: a rotation written in
numpy (by quadrature: R_sh[i, j] = ∫ y_i(s) y_j(R⁻¹ s) dΩ, numpy's
Gauss-Legendre nodes) passes the golden fixture; the same kernel given Rᵀ
gets the diagnosis text `shlab verify --diagnose` prints for a candidate
that `shlab verify --simulate inverse` wrote."""
import json
import os
import subprocess

import numpy as np
import pytest

import shlab
from shtruth import quad_nodes

pytestmark = pytest.mark.skipif(not shlab.verify_available(),
                                reason="the loaded libshlab has no verify.h functions yet")

_NODES = {}


def numpy_rotation_matrix(order, R, convention):
    """R_sh of order `order` by quadrature (exact: the integrand has band < 2·order)."""
    if order not in _NODES:
        d, w = quad_nodes(order, 2 * order + 1)
        _NODES[order] = (d, w, {})
    d, w, Y = _NODES[order]
    if convention not in Y:
        Y[convention] = shlab.eval_dir(order, d, convention)
    Yr = shlab.eval_dir(order, d @ R, convention)  # rows: y(Rᵀ s) (d @ R = (Rᵀ dᵀ)ᵀ)
    return Y[convention].T @ (w[:, None] * Yr)


def numpy_kernel(order, R, x, convention):
    return numpy_rotation_matrix(order, R, convention) @ x


def numpy_kernel_inverse(order, R, x, convention):
    return numpy_rotation_matrix(order, R.T, convention) @ x  # the deliberate mistake


@pytest.fixture(scope="module")
def orders(root):
    return shlab.load_fixture(os.path.join(root, "data/fixtures/rotation/orders_1_10.json"))


def test_fixture_fields_match_the_json(orders, root):
    raw = json.load(open(os.path.join(root, "data/fixtures/rotation/orders_1_10.json")))["cases"]
    assert len(orders) == len(raw) == 200
    for c, j in zip(orders.cases[::17], raw[::17]):
        assert c.id == j["id"] and c.order == j["order"] and c.band == -1 and c.convention == j["convention"]
        np.testing.assert_array_equal(c.input, j["input"])
        np.testing.assert_array_equal(c.expected, j["expected"])
        np.testing.assert_allclose(c.matrix.ravel(), j["rotation"]["matrix"], atol=1e-6)
        np.testing.assert_allclose(c.euler, j["rotation"]["euler"], atol=1e-12)
        assert c.tol_double == j["tolerance"]["double"] and c.tol_float == j["tolerance"]["float32"]
        assert not c.input.flags.writeable
    assert orders[raw[3]["id"]].index == 3


def test_numpy_kernel_passes(orders):
    r = shlab.verify(orders, numpy_kernel)
    assert r.passed and r.failed == 0 and r.cases == 200 and "diagnosis" not in r
    assert r.worst_error <= r.worst_tolerance


def test_inverse_mistake_gets_the_clis_diagnosis(orders, root, build, tmp_path):
    shlab_bin = os.path.join(build, "shlab")
    if not os.access(shlab_bin, os.X_OK):
        pytest.skip("no %s" % shlab_bin)
    fx = os.path.join(root, "data/fixtures/rotation/orders_1_10.json")
    cand = str(tmp_path / "cand.json")
    subprocess.run([shlab_bin, "verify", "--fixture", fx, "--method", "wigner", "--emit-candidate", cand,
                    "--simulate", "inverse", "--quiet"], check=True, capture_output=True)
    p = subprocess.run([shlab_bin, "verify", "--fixture", fx, "--candidate", cand, "--diagnose", "--quiet",
                        "--format", "json"], capture_output=True, text=True)
    assert p.returncode == 1, p.stderr
    cli = json.loads(p.stdout)
    py = shlab.verify(orders, numpy_kernel_inverse)
    assert not py.passed and py.mistake == "inverse"
    assert py.diagnosis == cli["diagnosis"]
    assert (py.diagnosis_matches, py.diagnosis_checked) == (cli["diagnosis_matches"], cli["diagnosis_checked"])
    assert py.failed == cli["failed"]
    # the candidate file itself, judged from Python: the CLI's JSON, field for field
    again = shlab.verify(orders, shlab.load_candidate(orders, cand), source=cand)
    d = again.as_dict()
    d["fixture"] = cli["fixture"] = None
    assert d == cli


def test_band_cases_get_full_vectors(root):
    bands = shlab.load_fixture(os.path.join(root, "data/fixtures/rotation/bands_50_200.json"))
    seen = []

    def kernel(order, R, x, conv):
        c = bands.cases[len(seen)]
        outside = np.ones(order * order, bool)
        outside[c.band_slice] = False
        seen.append((order, x.shape, np.all(x[outside] == 0)))
        return shlab.Stream(order, conv, threads=1).apply(shlab.Rotation.from_matrix(R), x)

    r = shlab.verify(bands, kernel)
    assert r.passed, r
    assert all(ok and shape == (order * order,) for order, shape, ok in seen) and len(seen) == 12


def test_dicts_simulations_and_precision(orders):
    ids = [c.id for c in orders]
    swap = {c.id: shlab.simulate(c, "swap") for c in orders}
    r = shlab.verify(orders, swap)
    assert r.mistake == "swap" and r.diagnosis == shlab.mistake_description("swap")
    # a float32 kernel: fails at double, passes at float, diagnosed as float precision only
    f32 = {c.id: (numpy_rotation_matrix(c.order, c.matrix, c.convention).astype(np.float32)
                  @ c.input.astype(np.float32)).astype(np.float64) for c in orders}
    d = shlab.verify(orders, f32)
    assert not d.passed and d.diagnosis.startswith("float precision only")
    assert shlab.verify(orders, f32, precision="float").passed
    # shlab's own method, and skipped cases
    direct = shlab.apply_method(orders, "direct")
    assert len(direct) == 60 and all(orders[k].order <= 3 for k in direct)
    r = shlab.verify(orders, direct)
    assert r.passed and r.skipped == 140
    assert set(shlab.mistakes()) >= {"convention", "inverse", "swap", "deg2rad", "mdesc"}
    assert ids[0] in swap


def test_verify_errors(orders, tmp_path):
    with pytest.raises(shlab.Error) as e:
        shlab.load_fixture(str(tmp_path / "missing.json"))
    assert e.value.status == 3 and "missing.json" in e.value.message
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "shlab-rotation-fixtures/1", "cases": []}')
    with pytest.raises(shlab.Error):
        shlab.load_fixture(str(bad))
    with pytest.raises(ValueError, match="shape"):
        shlab.verify(orders, lambda n, R, x, conv: x[:-1])
    with pytest.raises(ValueError, match="not in the fixture"):
        shlab.verify(orders, {"no-such-case": np.zeros(1)})
    with pytest.raises(ValueError, match="shape"):
        shlab.verify(orders, {orders[5].id: np.zeros(3)})
    with pytest.raises(shlab.Error):
        shlab.simulate(orders[0], "upside-down")
