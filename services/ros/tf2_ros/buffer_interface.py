"""How ``Buffer.transform(msg, target_frame)`` knows each message type: a table from type to the
function that applies a TransformStamped to it (tf2_ros's ``TransformRegistration``).

The geometry_msgs types register themselves (:mod:`.do_transform`), so ``buffer.transform``
works without ``import tf2_geometry_msgs`` first (in ROS it would raise TypeException). A
program may add its own: ``TransformRegistration().add(MyStamped, my_do_transform)``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from shared_models.errors import SkydeckError

__all__ = ["TransformRegistration", "TypeException"]

DoTransform = Callable[[Any, Any], Any]
_REGISTERED: dict[type, DoTransform] = {}


class TypeException(SkydeckError, TypeError):
    """``Buffer.transform`` met a type nobody registered a transform for."""

    def __init__(self, errstr: str) -> None:
        super().__init__(errstr)
        self.errstr = errstr


class TransformRegistration:
    """The table (one per process, as tf2_ros's class-level map)."""

    def add(self, key: type, callback: DoTransform) -> None:
        """Transform ``key`` messages with ``callback(msg, transform_stamped)``."""
        _REGISTERED[key] = callback

    def get(self, key: type) -> DoTransform:
        """The function for ``key``, or TypeException naming the types that have one."""
        try:
            return _REGISTERED[key]
        except KeyError:
            known = ", ".join(sorted(t.__name__ for t in _REGISTERED))
            raise TypeException(f"Type {key} is not loaded or supported (Buffer.transform takes: {known})") from None
