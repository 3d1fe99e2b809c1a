"""The windows' edge: one node of this process shows them through the one topic edge and the
one service path, like every other thing the dashboard shows.

On the node (the program's first ROS node, so its windows sit under its name; a node of their
own, ``/opencv_SCRIPT``, when the program has none):

    NODE/opencv/windows    skydeck_opencv/msg/Windows, latched: the windows, sizes, trackbars
    NODE/opencv/WINDOW     sensor_msgs/msg/CompressedImage (JPEG), latched: a window's image
    NODE/opencv/input      skydeck_opencv/srv/WindowInput: a key, mouse event or trackbar move

A window's name becomes a ROS name token (``video window`` -> ``video_window``); one that would
clash with another window's or with ``windows``/``input`` gets a number (``windows_2``). The
description carries each window's topic, so no viewer derives it.
"""

from __future__ import annotations

import functools
import re
import sys
import threading
from pathlib import Path

from services.ros.bridge import bridge
from services.ros.highgui.windows import InputHandler
from services.runtime.node import Node
from services.runtime.publisher import Publisher
from shared_models.sensor_msgs import CompressedImage
from shared_models.skydeck_opencv import WindowInput, Windows
from shared_models.std_msgs import Header

__all__ = ["NodeHost", "connect", "window_token"]

_RESERVED = frozenset({"windows", "input"})


def window_token(name: str, taken: set[str]) -> str:
    """A ROS name token for window ``name`` that is not in ``taken`` (nor reserved)."""
    token = re.sub(r"[^A-Za-z0-9_]", "_", name)
    if not token[:1].isalpha():
        token = "w_" + token
    candidate, number = token, 1
    while candidate in taken or candidate in _RESERVED:
        number += 1
        candidate = f"{token}_{number}"
    return candidate


class NodeHost:
    """Shows the windows through ``node``'s topics and serves their input (see the module)."""

    def __init__(self, node: Node, take_input: InputHandler) -> None:
        self._node = node
        self._lock = threading.Lock()
        self._tokens: dict[str, str] = {}  # window name -> its token; kept when it closes
        self._images: dict[str, Publisher[CompressedImage]] = {}  # topic -> publisher
        self._windows = bridge.call(
            functools.partial(node.create_publisher, Windows, "~/opencv/windows", 1, latched=True)
        )
        bridge.call(node.create_service, WindowInput, "~/opencv/input", take_input)

    def add_window(self, name: str) -> str:
        with self._lock:
            token = self._tokens.get(name)
            if token is None:
                token = self._tokens[name] = window_token(name, set(self._tokens.values()))
            topic = self._node.resolve_topic_name(f"~/opencv/{token}")
            if topic not in self._images:
                self._images[topic] = bridge.call(
                    functools.partial(self._node.create_publisher, CompressedImage, topic, 1, latched=True)
                )
            return topic

    def watched(self, topic: str) -> bool:
        return self._images[topic].get_subscription_count() > 0

    def publish_image(self, topic: str, jpeg: bytes) -> None:
        header = Header(stamp=self._node.get_clock().now().to_msg())
        bridge.call_soon(self._images[topic].publish, CompressedImage(header=header, format="jpeg", data=jpeg))

    def publish_windows(self, windows: Windows) -> None:
        bridge.call_soon(self._windows.publish, windows)


def connect(take_input: InputHandler) -> NodeHost:
    """The host on the program's first node, or on a node of the windows' own."""
    nodes = bridge.nodes
    if nodes:
        return NodeHost(nodes[0], take_input)
    script = Path(sys.argv[0]).stem if sys.argv and sys.argv[0] else "program"
    node = Node(f"opencv_{window_token(script, set())}")
    bridge.start_node(node)
    return NodeHost(node, take_input)
