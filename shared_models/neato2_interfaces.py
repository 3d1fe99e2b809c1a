"""neato2_interfaces: the Neato robot's Bump message, as the class's ROS 2 driver publishes it."""

from __future__ import annotations

from shared_models._message import Message, UInt8

__all__ = ["Bump"]


class Bump(Message):
    """The four bumper switches: 1 while that part of the bumper touches something, else 0.

    Course code reads them as truth values: ``if msg.left_front or msg.right_front: ...``.
    """

    __ros_type__ = "neato2_interfaces/msg/Bump"

    left_front: UInt8 = 0
    left_side: UInt8 = 0
    right_front: UInt8 = 0
    right_side: UInt8 = 0
