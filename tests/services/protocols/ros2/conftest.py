"""What the ROS 2 bridge's tests share: real ROS 2 (the `ros2` extra), kept out of other tests.

The extra installs top-level ``rclpy``, ``std_msgs``... into the venv. Tests that import them do
so through :func:`real_ros`, which takes them out of ``sys.modules`` again afterwards, so the
façade tests of ``services.ros`` (which put Skydeck's own ``std_msgs`` under that name) never meet
a real module left behind, and the other way round.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

import pytest

from services.protocols.ros2.extra import missing_extra


@pytest.fixture(scope="module")
def real_ros() -> Iterator[None]:
    """Real rclpy and message packages importable for the test; skipped without the extra."""
    reason = missing_extra()
    if reason is not None:
        pytest.skip(reason)
    before = set(sys.modules)
    from services.ros.imports import RosImportFinder

    hidden = [finder for finder in sys.meta_path if isinstance(finder, RosImportFinder)]
    for finder in hidden:
        sys.meta_path.remove(finder)
    stale = {name: module for name, module in sys.modules.items() if _is_ros(name)}
    for name in stale:
        del sys.modules[name]
    try:
        yield
    finally:
        for name in set(sys.modules) - before:
            if _is_ros(name):
                del sys.modules[name]
        sys.modules.update(stale)
        sys.meta_path[:0] = hidden


def _is_ros(name: str) -> bool:
    top = name.split(".", 1)[0]
    return top in {"rclpy", "rosidl_parser", "rpyutils"} or top.endswith(("_msgs", "_srvs", "_interfaces"))
