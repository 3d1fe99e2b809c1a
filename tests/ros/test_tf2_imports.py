"""tf2's ROS names inside a Skydeck process: ROS 2's tf2_ros, tf2_geometry_msgs and
tf_transformations, ROS 1's tf, tf.transformations and tf.msg, each the façade module."""

from __future__ import annotations

import importlib

import pytest

pytestmark = [pytest.mark.timeout(30), pytest.mark.usefixtures("ros_imports")]


@pytest.mark.parametrize(
    ("name", "facade"),
    [
        ("tf2_ros", "services.ros.tf2_ros"),
        ("tf2_ros.buffer", "services.ros.tf2_ros.buffer"),
        ("tf2_ros.transform_listener", "services.ros.tf2_ros.transform_listener"),
        ("tf2_ros.static_transform_broadcaster", "services.ros.tf2_ros.static_transform_broadcaster"),
        ("tf2_geometry_msgs", "services.ros.tf2_geometry_msgs"),
        ("tf_transformations", "services.ros.tf_transformations"),
        ("tf", "services.ros.tf"),
        ("tf.transformations", "services.ros.tf.transformations"),
        ("tf.msg", "services.ros.tf.msg"),
    ],
)
def test_tf_names_are_the_facades(name: str, facade: str) -> None:
    assert importlib.import_module(name) is importlib.import_module(facade)


def test_ros1_and_ros2_spellings_meet() -> None:
    import tf
    import tf2_ros
    import tf_transformations
    from tf.msg import tfMessage
    from tf2_msgs.msg import TFMessage

    assert tf.Exception is tf2_ros.TransformException and tf.LookupException is tf2_ros.LookupException
    assert tf.transformations.euler_from_quaternion is tf_transformations.euler_from_quaternion
    assert tfMessage is TFMessage
    with pytest.raises(Exception, match="tf2_ros.BufferClient is a ROS API Skydeck does not provide"):
        from tf2_ros import BufferClient  # noqa: F401
