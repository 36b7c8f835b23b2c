"""Rotation of coefficient vectors against numpy's linear algebra and the
closed-form basis: R_sh orthogonal, R_sh(AB) = R_sh(A) R_sh(B), the
rotated function equals f(R⁻¹ s) pointwise, band 1 is R itself in the p
basis; every input form, batch and precision agrees."""
import numpy as np
import pytest

import shlab
from shtruth import random_dirs, random_rotation, sh_closed

ORDER = 4


def rot(seed):
    return shlab.Rotation.from_matrix(random_rotation(seed))


@pytest.mark.parametrize("conv", ["cs", "nocs"])
@pytest.mark.parametrize("method", ["auto", "ivanic", "blanco", "wigner", "choi", "halfpi"])
def test_rotated_function_is_f_of_rinv_s(conv, method):
    # g(s) = f(R⁻¹ s): the closed-form basis at R⁻¹ s, written in numpy
    R = rot(11)
    c = np.random.default_rng(1).normal(size=16)
    g = shlab.Rotator(ORDER, method=method, convention=conv, threads=1).apply(c, R)
    d = random_dirs(40, 2)
    np.testing.assert_allclose(sh_closed(d, conv) @ g, sh_closed(d @ R.matrix, conv) @ c, atol=1e-13)


def test_band1_is_R_in_the_p_basis():
    # cs: (c_-1, c_0, c_1) = k(-a_y, a_z, -a_x) for f = a·s, and g = (R a)·s
    M = random_rotation(4)
    P = np.array([[0, -1, 0], [0, 0, 1], [-1, 0, 0]], dtype=float)
    Rsh = shlab.rotation_matrix(2, M)
    np.testing.assert_allclose(Rsh[1:4, 1:4], P @ M @ P.T, atol=1e-15)
    assert Rsh[0, 0] == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("method", ["zxzxz", "blanco", "halfpi", "ivanic"])
def test_orthogonal_and_homomorphism(method):
    order = 9
    A, B = rot(1), rot(2)
    RA = shlab.rotation_matrix(order, A, method)
    RB = shlab.rotation_matrix(order, B, method)
    RAB = shlab.rotation_matrix(order, A @ B, method)
    np.testing.assert_allclose(RA @ RA.T, np.eye(order * order), atol=1e-13)
    np.testing.assert_allclose(RAB, RA @ RB, atol=1e-13)
    c = np.random.default_rng(3).normal(size=order * order)
    assert np.linalg.norm(RA @ c) == pytest.approx(np.linalg.norm(c), rel=1e-14)


def test_every_input_form_agrees():
    r = shlab.Rotator(6, threads=1)
    c = np.random.default_rng(2).normal(size=(5, 36))
    A = rot(7)
    ref = r.apply(c, A)
    for form in (A.matrix, A.quat, np.array(A.euler)):
        np.testing.assert_allclose(r.apply(c, form), ref, atol=1e-14)
    np.testing.assert_allclose(r.apply(ref, A, inverse=True), c, atol=1e-14)
    np.testing.assert_allclose(r.apply(ref, A.inverse()), c, atol=1e-14)
    # in place
    x = c.copy()
    assert r.apply(x, A, out=x) is x
    np.testing.assert_allclose(x, ref, atol=0)


def test_float_agrees_with_double():
    c = np.random.default_rng(4).normal(size=(3, 25))
    A = rot(8)
    d = shlab.Rotator(5, precision="double", threads=1).apply(c, A)
    rf = shlab.Rotator(5, precision="float", threads=1)
    assert rf.precision == "float"
    f64 = rf.apply(c, A)
    f32 = rf.apply(c.astype(np.float32), A.matrix.astype(np.float32))
    assert f64.dtype == np.float64 and f32.dtype == np.float32
    np.testing.assert_allclose(f64, d, atol=2e-6)
    np.testing.assert_allclose(f32, d, atol=2e-6)
    assert np.max(np.abs(f64 - d)) > 0  # it really computed in float


@pytest.mark.parametrize("prec", ["double", "float"])
def test_plan_batches(prec):
    dt = np.float32 if prec == "float" else np.float64
    tol = 3e-6 if prec == "float" else 1e-14
    rr = shlab.Rotator(4, precision=prec, threads=1)
    plan = rr.plan()
    K = 7
    rots = [rot(20 + k) for k in range(K)]
    X = np.random.default_rng(5).normal(size=(K, 16))
    ref = np.stack([shlab.rotation_matrix(4, rots[k]) @ X[k] for k in range(K)])
    plan.set(rots[0])
    np.testing.assert_allclose(plan.apply(X.astype(dt)), X @ shlab.rotation_matrix(4, rots[0]).T, atol=tol)
    soa = np.ascontiguousarray(X.T, dtype=dt)
    np.testing.assert_allclose(plan.apply_many(soa).T, X @ shlab.rotation_matrix(4, rots[0]).T, atol=tol)
    got = plan.rotate_many(np.stack([r.matrix for r in rots]), soa)
    np.testing.assert_allclose(got.T, ref, atol=tol)
    got = plan.rotate_many(np.stack([r.quat for r in rots]), soa)
    np.testing.assert_allclose(got.T, ref, atol=tol)
    with pytest.raises(ValueError, match="structure of arrays"):
        plan.apply_many(X.astype(dt))
    with pytest.raises(ValueError, match="K = 7"):
        plan.rotate_many(np.stack([r.matrix for r in rots[:3]]), soa)


def test_plan_blocks_and_set_forms():
    plan = shlab.Rotator(3, method="blanco", threads=1).plan()
    A = rot(9)
    b1 = [b.copy() for b in plan.set(A).blocks()]
    b2 = plan.set(A.matrix).blocks()
    b3 = plan.set(A.quat).blocks()
    assert [b.shape for b in b1] == [(1, 1), (3, 3), (5, 5)]
    for x, y, z in zip(b1, b2, b3):
        np.testing.assert_allclose(x, y, atol=1e-14)
        np.testing.assert_allclose(x, z, atol=1e-14)


def test_stream_and_band():
    order = 40
    rots = [rot(30), rot(31)]
    X = np.random.default_rng(6).normal(size=(2, order * order))
    s = shlab.Stream(order, threads=1)
    got = s.apply(rots, X)
    assert got.shape == (2, 2, order * order)
    ref = shlab.Rotator(order, method="zxzxz", threads=1)
    for r in range(2):
        np.testing.assert_allclose(got[r], ref.apply(X, rots[r]), atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(got[r], axis=1), np.linalg.norm(X, axis=1), rtol=1e-13)
    np.testing.assert_allclose(s.apply(rots[0], got[0], inverse=True), X, atol=1e-12)
    l = 25
    band = X[:, l * l:(l + 1) * (l + 1)]
    np.testing.assert_allclose(shlab.rotate_band(l, rots[1], band), got[1][:, l * l:(l + 1) * (l + 1)], atol=1e-12)


def test_rotator_properties_and_errors():
    r = shlab.Rotator(40, threads=1)
    assert r.method == "halfpi" and r.order == 40  # auto above order 32
    assert shlab.Rotator(4, threads=1).method == "zxzxz"
    with pytest.raises(shlab.Error) as e:
        shlab.Rotator(5, method="direct")
    assert e.value.status == 1 and "direct" in e.value.message
    with pytest.raises(shlab.Error, match="order 0"):
        shlab.Rotator(0)
    with pytest.raises(shlab.Error):
        shlab.Rotator(4, method="euler-magic")
    r = shlab.Rotator(3, threads=1)
    with pytest.raises(ValueError, match=r"\(\.\.\., 9\)"):
        r.apply(np.zeros(16), rot(1))
    with pytest.raises(TypeError):
        r.apply(np.zeros(9, dtype=complex), rot(1))
    with pytest.raises(shlab.Error):
        r.apply(np.zeros(9), np.diag([1.0, -1.0, 1.0]))  # not a proper rotation: shlab refuses
    with pytest.raises(ValueError, match="rotation"):
        r.apply(np.zeros(9), np.zeros(5))
    with pytest.raises(TypeError, match="float32"):
        shlab.Rotator(3, precision="float", threads=1).plan().apply_many(np.zeros((9, 2)))
