"""The simulator's camera on two topics, rendered only while someone reads one of them:

- ``/simulator/camera`` (sensor_msgs/msg/CompressedImage, JPEG): the name it always had, so the
  dashboard, the 3D view and existing clients keep working;
- ``/simulator/camera/image_raw`` (sensor_msgs/msg/Image, ``rgb8``): the raw pixels, named as
  a ROS camera driver names them.

Both come from one render per tick, at the resolution and rate of the node's parameters
``camera_width``, ``camera_height`` and ``camera_rate`` (from the flags ``--camera-width``...;
settable while running: ``skydeck param set /sim camera_rate 10``). A render that takes longer
than the period delays the next tick instead of queueing renders (the timer skips, never bursts).
"""

from __future__ import annotations

from collections.abc import Callable

from services.runtime import Node
from services.runtime.parameter import Parameter
from shared_models.rcl_interfaces import FloatingPointRange, IntegerRange, ParameterDescriptor
from shared_models.sensor_msgs import CompressedImage, Image
from shared_models.std_msgs import Header
from sim_server.camera import encode_jpeg
from sim_server.settings import (
    MAX_CAMERA_HEIGHT,
    MAX_CAMERA_RATE_HZ,
    MAX_CAMERA_WIDTH,
    MIN_CAMERA_RATE_HZ,
    MIN_CAMERA_SIDE,
    SimSettings,
)

__all__ = ["COMPRESSED_TOPIC", "RAW_TOPIC", "CameraStream"]

COMPRESSED_TOPIC = "/simulator/camera"
RAW_TOPIC = "/simulator/camera/image_raw"
JPEG_QUALITY = 70


class CameraStream:
    """Publishes what ``render(width, height)`` (rgb8 bytes) sees, while anyone reads it, on
    ``node``'s topics, starting at ``sim``'s size and rate."""

    def __init__(
        self, node: Node, sim: SimSettings, render: Callable[[int, int], bytes], header: Callable[[], Header]
    ) -> None:
        self._render = render
        self._header = header
        self.width = self._declare(node, "camera_width", sim.camera_width, MAX_CAMERA_WIDTH, "image width, pixels")
        self.height = self._declare(node, "camera_height", sim.camera_height, MAX_CAMERA_HEIGHT, "image height, pixels")
        self.rate_hz = float(
            node.declare_parameter(
                "camera_rate",
                float(sim.camera_rate),
                ParameterDescriptor(
                    description="camera frames a second (wall time), while someone reads them",
                    floating_point_range=[
                        FloatingPointRange(from_value=MIN_CAMERA_RATE_HZ, to_value=MAX_CAMERA_RATE_HZ)
                    ],
                ),
            ).value
        )
        self.compressed = node.create_publisher(CompressedImage, COMPRESSED_TOPIC, 2)
        self.raw = node.create_publisher(Image, RAW_TOPIC, 2)
        self.timer = node.create_timer(1.0 / self.rate_hz, self.publish, wall_clock=True)
        node.add_post_set_parameters_callback(self._changed)

    @staticmethod
    def _declare(node: Node, name: str, value: int, maximum: int, description: str) -> int:
        descriptor = ParameterDescriptor(
            description=description, integer_range=[IntegerRange(from_value=MIN_CAMERA_SIDE, to_value=maximum)]
        )
        return int(node.declare_parameter(name, value, descriptor).value)

    def _changed(self, parameters: list[Parameter]) -> None:
        for parameter in parameters:
            if parameter.name == "camera_width":
                self.width = int(parameter.value)
            elif parameter.name == "camera_height":
                self.height = int(parameter.value)
            elif parameter.name == "camera_rate":
                self.rate_hz = float(parameter.value)
                self.timer.timer_period_s = 1.0 / self.rate_hz
                self.timer.reset()

    def publish(self) -> None:
        """One render for both topics, and each only if someone reads it (rendering costs
        tens of milliseconds; nobody watching costs nothing)."""
        raw_wanted = self.raw.get_subscription_count() > 0
        jpeg_wanted = self.compressed.get_subscription_count() > 0
        if not (raw_wanted or jpeg_wanted):
            return
        width, height = self.width, self.height
        pixels = self._render(width, height)
        if raw_wanted:
            self.raw.publish(
                Image(header=self._header(), height=height, width=width, encoding="rgb8", step=3 * width, data=pixels)
            )
        if jpeg_wanted:
            jpeg = encode_jpeg(pixels, width, height, JPEG_QUALITY)
            self.compressed.publish(CompressedImage(header=self._header(), format="jpeg", data=jpeg))
