"""skydeck_opencv: a node's OpenCV windows, as the dashboard shows them.

A program that ``skydeck run`` starts on a machine without a display has its OpenCV windows
(``cv2.namedWindow``, ``imshow``, trackbars, mouse callbacks, ``waitKey``) served by Skydeck
(``services/ros/highgui``). The node that hosts them says which windows it has on
``NODE/opencv/windows`` (:class:`Windows`, latched), publishes each window's image as a
``sensor_msgs/CompressedImage`` on the window's ``topic``, and takes what a viewer does in a
window (a key, a mouse event, a trackbar moved) through the service ``NODE/opencv/input``
(:class:`WindowInput`).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field

from shared_models._message import Bool, Int32, Message, ServiceType, String, UInt32

__all__ = [
    "Trackbar",
    "Window",
    "WindowInput",
    "WindowInputRequest",
    "WindowInputResponse",
    "Windows",
]


class Trackbar(Message):
    """A trackbar of a window (``cv2.createTrackbar``): its position within ``[minimum, maximum]``."""

    __ros_type__ = "skydeck_opencv/msg/Trackbar"

    name: String = ""
    value: Int32 = 0
    minimum: Int32 = 0
    maximum: Int32 = 0


class Window(Message):
    """One OpenCV window: its name, where its image is published, the image's size (0 before the
    first ``imshow``), the size ``cv2.resizeWindow`` asked for (0: the image's own), whether a
    mouse callback listens, and its trackbars in the order they were created."""

    __ros_type__ = "skydeck_opencv/msg/Window"

    name: String = ""
    title: String = ""
    topic: String = ""
    width: UInt32 = 0
    height: UInt32 = 0
    display_width: UInt32 = 0
    display_height: UInt32 = 0
    mouse: Bool = False
    trackbars: list[Trackbar] = Field(default_factory=list)


class Windows(Message):
    """Every OpenCV window of a node, in the order they were made."""

    __ros_type__ = "skydeck_opencv/msg/Windows"

    windows: list[Window] = Field(default_factory=list)


class WindowInputRequest(Message):
    """What a viewer did in ``window``: a ``key`` typed (the code ``cv2.waitKeyEx`` returns), a
    mouse ``event`` (OpenCV's ``EVENT_*``) at image pixel (``x``, ``y``) with OpenCV's ``flags``,
    or ``trackbar`` moved to ``value``. ``kind`` is one of the constants."""

    __ros_type__ = "skydeck_opencv/srv/WindowInput_Request"
    __ros_constants__ = ("KEY", "MOUSE", "TRACKBAR")

    KEY: ClassVar[String] = "key"
    MOUSE: ClassVar[String] = "mouse"
    TRACKBAR: ClassVar[String] = "trackbar"

    window: String = ""
    kind: String = ""
    key: Int32 = 0
    event: Int32 = 0
    x: Int32 = 0
    y: Int32 = 0
    flags: Int32 = 0
    trackbar: String = ""
    value: Int32 = 0


class WindowInputResponse(Message):
    """Whether the input was taken (the program sees it at its next ``cv2.waitKey``), or why not."""

    __ros_type__ = "skydeck_opencv/srv/WindowInput_Response"

    success: Bool = False
    message: String = ""


class WindowInput(ServiceType):
    """A key, mouse event or trackbar move for one of the node's OpenCV windows."""

    __ros_type__ = "skydeck_opencv/srv/WindowInput"
    Request = WindowInputRequest
    Response = WindowInputResponse
