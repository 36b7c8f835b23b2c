"""Rotation constructors against numpy's matrices: ZYZ Euler angles as
Rz Ry Rz, quaternions by the textbook formula, composition as the matrix
product, inverse as the transpose."""
import numpy as np
import pytest

import shlab
from shtruth import random_rotation, ry, rz


def quat_matrix(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def test_euler_is_zyz_active():
    a, b, g = 0.3, 1.1, -2.0
    r = shlab.Rotation.from_euler(a, b, g)
    np.testing.assert_allclose(r.matrix, rz(a) @ ry(b) @ rz(g), atol=1e-15)
    np.testing.assert_allclose(r.euler, (a, b, g), atol=1e-15)


def test_quat_and_matrix_and_axis_angle():
    q = np.array([0.5, -0.1, 0.7, 0.3])
    q /= np.linalg.norm(q)
    r = shlab.Rotation.from_quat(q)
    np.testing.assert_allclose(r.matrix, quat_matrix(q), atol=1e-15)
    np.testing.assert_allclose(r.quat, q * np.sign(q[0]), atol=1e-15)
    M = random_rotation(3)
    np.testing.assert_allclose(shlab.Rotation.from_matrix(M).matrix, M, atol=1e-15)
    r = shlab.Rotation.from_axis_angle([0, 0, 2.0], 0.5)
    np.testing.assert_allclose(r.matrix, rz(0.5), atol=1e-15)
    axis, angle = r.axis_angle
    np.testing.assert_allclose(axis, [0, 0, 1], atol=1e-15)
    assert abs(angle - 0.5) < 1e-15


def test_compose_and_inverse():
    A, B = shlab.Rotation.from_matrix(random_rotation(1)), shlab.Rotation.from_matrix(random_rotation(2))
    np.testing.assert_allclose((A @ B).matrix, A.matrix @ B.matrix, atol=1e-15)
    np.testing.assert_allclose(A.inverse().matrix, A.matrix.T, atol=1e-15)


def test_refusals_carry_shlabs_message():
    with pytest.raises(shlab.Error) as e:
        shlab.Rotation.from_matrix(np.diag([1.0, 1.0, -1.0]))
    assert e.value.status == 1 and e.value.message
    with pytest.raises(shlab.Error):
        shlab.Rotation.from_matrix(np.ones((3, 3)))
    with pytest.raises(shlab.Error):
        shlab.Rotation.from_quat([2.0, 0, 0, 0])
    ok = shlab.Rotation.from_quat([2.0, 0, 0, 0], orthonormalize=True)
    np.testing.assert_allclose(ok.matrix, np.eye(3), atol=0)
    with pytest.raises(ValueError):
        shlab.Rotation.from_matrix(np.eye(4))
    with pytest.raises(TypeError):
        shlab.Rotation.from_euler("a", 0, 0)
