"""Each robot's forward camera, as the Neato's camera driver publishes it: per robot, under its
namespace,

    camera/image_raw     sensor_msgs/msg/Image, ``rgb8`` (what the Neato's camera driver and
                         Gazebo's camera publish; course code asks cv_bridge for ``bgr8``)
    camera/camera_info   sensor_msgs/msg/CameraInfo: the pinhole the renderer draws with

in frame ``camera`` (``robot1/camera`` with several robots; ``base_link -> camera`` is on
``/tf_static``), an optical frame as ROS's cameras have (z ahead, x right, y down), looking a
little down.

A camera renders only while someone reads its image, at the simulator's camera rate and size
(``--camera-rate``, ``--camera-width``/``--camera-height``, the ``camera_*`` parameters the
simulator's own camera has too); its camera_info goes out at that rate while read, whether or
not the image is. A render that takes longer than the period delays the next tick rather than
queueing renders.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from services.runtime.parameter import Parameter
from shared_models.sensor_msgs import CameraInfo, Image
from shared_models.std_msgs import Header
from sim_server.camera import View, render_rgb
from sim_server.soccer.limits import (
    CAMERA_FAR_M,
    CAMERA_FORWARD_M,
    CAMERA_HEIGHT_M,
    CAMERA_NEAR_M,
    CAMERA_PITCH_DEG,
    CAMERA_VERTICAL_FOV_DEG,
)

if TYPE_CHECKING:
    from sim_server.camera_stream import CameraStream
    from sim_server.world_node import WorldNode

__all__ = ["CAMERA_FRAME", "RobotCameras", "camera_frame", "camera_info", "camera_view"]

CAMERA_FRAME = "camera"
_LOOK_AHEAD_M = 1.0


def camera_frame(namespace: str) -> str:
    """The camera's frame for the robot under ``namespace`` (prefixed as its other frames are)."""
    return CAMERA_FRAME if namespace == "/" else f"{namespace.strip('/')}/{CAMERA_FRAME}"


def camera_view(x: float, y: float, yaw: float) -> View:
    """Where the camera of a robot at (x, y) facing ``yaw`` stands and looks."""
    c, s = math.cos(yaw), math.sin(yaw)
    eye = (x + CAMERA_FORWARD_M * c, y + CAMERA_FORWARD_M * s, CAMERA_HEIGHT_M)
    drop = _LOOK_AHEAD_M * math.tan(math.radians(CAMERA_PITCH_DEG))
    target = (eye[0] + _LOOK_AHEAD_M * c, eye[1] + _LOOK_AHEAD_M * s, CAMERA_HEIGHT_M - drop)
    return View(eye, target, near_m=CAMERA_NEAR_M, far_m=CAMERA_FAR_M)


def camera_info(header: Header, width: int, height: int) -> CameraInfo:
    """The camera's calibration at ``width`` x ``height``: square pixels, the centre in the
    middle, no distortion (a renderer's pinhole)."""
    focal = (height / 2.0) / math.tan(math.radians(CAMERA_VERTICAL_FOV_DEG) / 2.0)
    cx, cy = width / 2.0, height / 2.0
    return CameraInfo(
        header=header,
        width=width,
        height=height,
        distortion_model="plumb_bob",
        d=[0.0] * 5,
        k=[focal, 0.0, cx, 0.0, focal, cy, 0.0, 0.0, 1.0],
        r=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        p=[focal, 0.0, cx, 0.0, 0.0, focal, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
    )


class _Camera:
    """One robot's camera topics."""

    def __init__(self, node: WorldNode, robot: int, namespace: str) -> None:
        base = "" if namespace == "/" else namespace
        self.robot = robot
        self.frame = camera_frame(namespace)
        self.image = node.create_publisher(Image, f"{base}/camera/image_raw", 2)
        self.info = node.create_publisher(CameraInfo, f"{base}/camera/camera_info", 2)


class RobotCameras:
    """Every robot's camera on ``node``; ``pose(robot)`` says where robot ``robot`` is (x, y, yaw)."""

    def __init__(
        self,
        node: WorldNode,
        namespaces: Sequence[str],
        pose: Callable[[int], tuple[float, float, float]],
        client: Callable[[], int],
    ) -> None:
        self._node = node
        self._pose = pose
        self._client = client
        self._stream: CameraStream = node.camera  # its size and rate are the cameras' too
        self.cameras = [_Camera(node, i, ns) for i, ns in enumerate(namespaces)]
        self.timer = node.create_timer(1.0 / self._stream.rate_hz, self.publish, wall_clock=True)
        node.add_post_set_parameters_callback(self._changed)

    def _changed(self, parameters: list[Parameter]) -> None:
        if any(parameter.name == "camera_rate" for parameter in parameters):
            self.timer.timer_period_s = 1.0 / self._stream.rate_hz
            self.timer.reset()

    def publish(self) -> None:
        """One tick: each camera that someone reads renders once."""
        width, height = self._stream.width, self._stream.height
        for camera in self.cameras:
            image_read = camera.image.get_subscription_count() > 0
            if not (image_read or camera.info.get_subscription_count() > 0):
                continue
            header = self._node.header(camera.frame)
            camera.info.publish(camera_info(header.model_copy(), width, height))
            if image_read:
                pixels = render_rgb(self._client(), camera_view(*self._pose(camera.robot)), width, height)
                camera.image.publish(
                    Image(header=header, height=height, width=width, encoding="rgb8", step=3 * width, data=pixels)
                )
