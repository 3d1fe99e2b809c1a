"""tf_transformations / tf.transformations against known values and round trips: quaternions in
ROS's [x, y, z, w] order, all 24 Euler conventions (static and rotating frames, repeated axes,
gimbal lock), matrices, slerp, and composition/decomposition."""

from __future__ import annotations

import math

import numpy as np
import pytest

from services.ros import tf_transformations as t
from services.ros.errors import NotProvidedError
from services.ros.tf_transformations.euler import AXES

pytestmark = pytest.mark.timeout(30)


def _same_rotation(q0: np.ndarray, q1: np.ndarray) -> bool:
    return bool(np.allclose(q0, q1) or np.allclose(q0, -q1))


def test_known_values_in_ros_order() -> None:
    assert np.allclose(t.quaternion_from_euler(0.0, 0.0, math.pi / 2), [0, 0, math.sqrt(0.5), math.sqrt(0.5)])
    assert np.allclose(t.quaternion_from_euler(math.pi, 0.0, 0.0), [1, 0, 0, 0])
    assert np.allclose(t.quaternion_from_euler(1, 2, 3, "ryxz"), [0.310622, -0.718287, 0.444435, 0.435953], atol=1e-6)
    assert np.allclose(t.euler_from_quaternion([0.06146124, 0, 0, 0.99810947]), [0.123, 0, 0], atol=1e-7)
    assert math.isclose(float(np.sum(t.euler_matrix(1, 2, 3, "syxz")[0])), -1.34786452, abs_tol=1e-8)
    assert np.allclose(t.quaternion_multiply([1, -2, 3, 4], [-5, 6, 7, 8]), [-44, -14, 48, 28])
    assert np.allclose(t.quaternion_conjugate([1, 2, 3, 4]), [-1, -2, -3, 4])
    assert np.allclose(t.quaternion_about_axis(math.pi, [0, 0, 2]), [0, 0, 1, 0], atol=1e-12)
    assert t.quaternion_real([1, 2, 3, 4]) == 4.0 and np.allclose(t.quaternion_imag([1, 2, 3, 4]), [1, 2, 3])


def test_a_yaw_rotation_turns_x_into_y() -> None:
    rotation = t.euler_matrix(0.0, 0.0, math.pi / 2)
    assert np.allclose(rotation @ [1, 0, 0, 1], [0, 1, 0, 1])
    assert np.allclose(t.quaternion_matrix(t.quaternion_from_euler(0.0, 0.0, math.pi / 2)), rotation)


@pytest.mark.parametrize("axes", AXES)
def test_every_convention_round_trips_through_matrix_and_quaternion(axes: str) -> None:
    rng = np.random.default_rng(7)
    for _ in range(50):
        angles = rng.uniform(-math.pi, math.pi, 3)
        matrix = t.euler_matrix(*angles, axes=axes)
        back = t.euler_from_matrix(matrix, axes)
        assert np.allclose(t.euler_matrix(*back, axes=axes), matrix)  # the same rotation (angles may alias)
        q = t.quaternion_from_euler(*angles, axes=axes)
        assert np.allclose(t.quaternion_matrix(q), matrix)
        assert np.allclose(t.euler_matrix(*t.euler_from_quaternion(q, axes), axes=axes), matrix)
    if axes[1] != axes[3]:  # three axes: angles in range come back as they were
        assert t.euler_from_matrix(t.euler_matrix(0.3, 0.4, 0.5, axes=axes), axes) == pytest.approx((0.3, 0.4, 0.5))


@pytest.mark.parametrize("axes", AXES)
def test_gimbal_lock_keeps_the_rotation_and_zeroes_one_angle(axes: str) -> None:
    repeated = axes[1] == axes[3]
    matrix = t.euler_matrix(0.3, 0.0 if repeated else math.pi / 2, 0.5, axes=axes)
    angles = t.euler_from_matrix(matrix, axes)
    assert np.allclose(t.euler_matrix(*angles, axes=axes), matrix)
    assert 0.0 in (angles[0], angles[2])


def test_static_and_rotating_frames_mirror_each_other() -> None:
    a, b, c = 0.1, 0.2, 0.3
    assert np.allclose(t.euler_matrix(a, b, c, "sxyz"), t.euler_matrix(c, b, a, "rzyx"))
    # rotating axes: about x, then the new y, then the newer z
    assert np.allclose(t.euler_matrix(a, b, c, "rxyz"), t.rotation_matrix(a, [1, 0, 0]) @ t.rotation_matrix(b, [0, 1, 0]) @ t.rotation_matrix(c, [0, 0, 1]))


def test_unknown_axes_say_which_exist() -> None:
    with pytest.raises(ValueError, match="unknown axes 'xyz': one of 'sxyz'"):
        t.euler_matrix(0, 0, 0, "xyz")


def test_inverse_and_product_of_quaternions() -> None:
    q = t.random_quaternion([0.1, 0.2, 0.3])
    assert math.isclose(float(np.linalg.norm(q)), 1.0)
    assert np.allclose(t.quaternion_multiply(q, t.quaternion_inverse(q)), [0, 0, 0, 1])
    q2 = t.quaternion_from_euler(0.4, -0.2, 1.0)
    assert np.allclose(t.quaternion_matrix(t.quaternion_multiply(q2, q)), t.quaternion_matrix(q2) @ t.quaternion_matrix(q))
    assert _same_rotation(t.quaternion_from_matrix(t.quaternion_matrix(q)), q)
    assert t.quaternion_from_matrix(t.euler_matrix(0.0, 0.0, 3.0))[3] >= 0.0  # w >= 0, as ROS 2's


def test_slerp_ends_middle_and_shortest_path() -> None:
    q0 = t.quaternion_from_euler(0.0, 0.0, 0.0)
    q1 = t.quaternion_from_euler(0.0, 0.0, 1.0)
    assert np.allclose(t.quaternion_slerp(q0, q1, 0.0), q0) and np.allclose(t.quaternion_slerp(q0, q1, 1.0), q1)
    assert np.allclose(t.quaternion_slerp(q0, q1, 0.5), t.quaternion_from_euler(0.0, 0.0, 0.5))
    far = -t.quaternion_from_euler(0.0, 0.0, 1.0)  # the same rotation, the other sign
    assert _same_rotation(t.quaternion_slerp(q0, far, 0.5), t.quaternion_from_euler(0.0, 0.0, 0.5))


def test_matrices_translate_rotate_scale_and_invert() -> None:
    move = t.translation_matrix([1, 2, 3])
    assert np.allclose(t.translation_from_matrix(move), [1, 2, 3])
    turn = t.rotation_matrix(math.pi / 2, [0, 0, 1], point=[1, 0, 0])  # about a vertical axis through (1, 0, 0)
    assert np.allclose(turn @ [2, 0, 0, 1], [1, 1, 0, 1])
    angle, direction, point = t.rotation_from_matrix(turn)
    assert math.isclose(angle, math.pi / 2) and np.allclose(direction, [0, 0, 1]) and np.allclose(turn @ point, point)
    both = t.concatenate_matrices(move, turn)
    assert np.allclose(both, move @ turn) and t.is_same_transform(t.inverse_matrix(both) @ both, t.identity_matrix())
    assert np.allclose(t.scale_matrix(2.0, origin=[1, 1, 1]) @ [2, 1, 1, 1], [3, 1, 1, 1])
    assert np.allclose(t.unit_vector([3.0, 4.0]), [0.6, 0.8]) and t.vector_norm([3.0, 4.0]) == 5.0
    assert np.allclose(t.random_rotation_matrix([0.5, 0.5, 0.5])[:3, :3] @ t.random_rotation_matrix([0.5, 0.5, 0.5])[:3, :3].T, np.eye(3))


def test_compose_and_decompose_are_inverses() -> None:
    parts = ([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], [0.4, 0.5, 0.6], [1.0, 2.0, 3.0], [0.0, 0.0, 0.0, 1.0])
    matrix = t.compose_matrix(*parts)
    for got, wanted in zip(t.decompose_matrix(matrix), parts, strict=True):
        assert np.allclose(got, wanted)
    mirrored = t.compose_matrix([-1.0, 2.0, 3.0], None, [0.4, 0.5, 0.6], None, [0.01, 0.02, 0.03, 1.0])
    assert np.allclose(t.compose_matrix(*t.decompose_matrix(mirrored)), mirrored)
    with pytest.raises(ValueError, match="singular"):
        t.decompose_matrix(np.diag([1.0, 0.0, 1.0, 1.0]))


def test_the_rarer_functions_name_themselves() -> None:
    with pytest.raises(NotProvidedError, match="tf_transformations.shear_matrix is a ROS API Skydeck does not provide"):
        t.shear_matrix  # noqa: B018
    with pytest.raises(AttributeError):
        t.no_such_function  # noqa: B018
