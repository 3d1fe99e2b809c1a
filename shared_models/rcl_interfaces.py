"""rcl_interfaces: Log, the message of the ``/rosout`` topic."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field

from shared_models._message import Message, String, UInt8, UInt32
from shared_models.builtin_interfaces import Time

__all__ = ["Log"]


class Log(Message):
    """One log record of a node, as published on ``/rosout``; ``level`` is one of the constants."""

    __ros_type__ = "rcl_interfaces/msg/Log"
    __ros_comment__ = (
        "# Severity level constants: they follow Python's logging levels.\n"
        "# The name of the node is in name, the logged text in msg."
    )
    __ros_constants__ = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")

    DEBUG: ClassVar[UInt8] = 10
    INFO: ClassVar[UInt8] = 20
    WARN: ClassVar[UInt8] = 30
    ERROR: ClassVar[UInt8] = 40
    FATAL: ClassVar[UInt8] = 50

    stamp: Time = Field(default_factory=Time)
    level: UInt8 = 0
    name: String = ""
    msg: String = ""
    file: String = ""
    function: String = ""
    line: UInt32 = 0
