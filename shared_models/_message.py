"""The base of every Skydeck message and service type.

A message is a pydantic v2 model whose field names, defaults and JSON match the ROS message of
the same name, so ROS code reads the same: ``Point(x=1.0, y=2.0, z=0.0)``. Each concrete type
declares its ROS name in ``__ros_type__`` (``"geometry_msgs/msg/Point"``), which registers it
for lookup by name (:func:`shared_models.get_interface`, which loads the package it names).

Field types carry their ROS primitive through ``Annotated`` aliases (``Float64``, ``UInt32``...),
which is what ``skydeck interface show`` prints.

Messages also behave like ROS 1's (genpy) in Python: ``Point(1.0, 2.0, 3.0)`` fills the fields in
order, ``msg.linear.x = 0.1`` mutates, and the ``.msg`` constants are class attributes
(``Marker.ARROW``), never fields.
"""

from __future__ import annotations

import base64
import binascii
import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Annotated, Any, ClassVar

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PlainSerializer,
    Strict,
    ValidationInfo,
    WithJsonSchema,
)

__all__ = [
    "ActionType",
    "Base64Bytes",
    "Bool",
    "Byte",
    "ByteArray",
    "Declared",
    "Float32",
    "Float64",
    "Int8",
    "Int16",
    "Int32",
    "Int64",
    "Message",
    "Ros1Only",
    "RosPrimitive",
    "ServiceType",
    "String",
    "UInt8",
    "UInt8Array",
    "UInt16",
    "UInt32",
    "UInt64",
    "fixed_floats",
    "forget_interfaces",
    "registered",
]


@dataclass(frozen=True)
class RosPrimitive:
    """Marks a field with the ROS primitive type it stands for (``float64``, ``uint32``...)."""

    name: str


@dataclass(frozen=True)
class Declared:
    """Marks a field whose ``.msg`` file spells out its default (``bool read_only false``), so
    ``interface show`` prints it even where it is the type's zero."""


@dataclass(frozen=True)
class Ros1Only:
    """Marks a field that ROS 2's type of the same name does not have (``Header.seq``, kept from
    ROS 1): left out of the type's ROS 2 definition and CDR (:mod:`shared_models.ros2msg`)."""


# Strict: JSON `true` is not the number 1 and "3" is not the integer 3 (lax pydantic would
# coerce both); an integer is still a valid float, and nested messages still take dicts.
Bool = Annotated[bool, Strict(), RosPrimitive("bool")]
Byte = Annotated[int, Strict(), RosPrimitive("byte"), Field(ge=0, le=0xFF)]
UInt8 = Annotated[int, Strict(), RosPrimitive("uint8"), Field(ge=0, le=0xFF)]
Int8 = Annotated[int, Strict(), RosPrimitive("int8"), Field(ge=-(2**7), le=2**7 - 1)]
UInt16 = Annotated[int, Strict(), RosPrimitive("uint16"), Field(ge=0, le=0xFFFF)]
Int16 = Annotated[int, Strict(), RosPrimitive("int16"), Field(ge=-(2**15), le=2**15 - 1)]
Int32 = Annotated[int, Strict(), RosPrimitive("int32"), Field(ge=-(2**31), le=2**31 - 1)]
UInt32 = Annotated[int, Strict(), RosPrimitive("uint32"), Field(ge=0, le=2**32 - 1)]
Int64 = Annotated[int, Strict(), RosPrimitive("int64"), Field(ge=-(2**63), le=2**63 - 1)]
UInt64 = Annotated[int, Strict(), RosPrimitive("uint64"), Field(ge=0, le=2**64 - 1)]
Float32 = Annotated[float, Strict(), RosPrimitive("float32")]
Float64 = Annotated[float, Strict(), RosPrimitive("float64")]
String = Annotated[str, Strict(), RosPrimitive("string")]


def _base64_pattern() -> str:
    """Exactly the text pydantic's base64 reading takes: one alphabet (standard or URL-safe),
    padding optional, no stray bits in the last character; so the schema says what is accepted."""

    def one(alphabet: str) -> str:
        return rf"(?:{alphabet}{{4}})*(?:{alphabet}[AQgw](?:==?)?|{alphabet}{{2}}[AEIMQUYcgkosw048]=?)?"

    return rf"^(?:{one('[A-Za-z0-9+/]')}|{one('[A-Za-z0-9_-]')})$"


_BASE64 = re.compile(_base64_pattern())


def _bytes_from(value: Any, info: ValidationInfo) -> Any:
    # A list of ints is how ROS (and rosbridge's input) spells uint8[]. In Python mode a str is
    # the base64 text of a JSON frame that went through json.loads (e.g. `skydeck topic pub`);
    # in JSON mode pydantic's val_json_bytes="base64" decodes it.
    if isinstance(value, list):
        # 5.0 is an integer to JSON Schema (and to a JavaScript client); true is not
        items = [int(i) if type(i) is float and i.is_integer() else i for i in value]
        if not all(type(item) is int and 0 <= item <= 0xFF for item in items):
            raise ValueError("a uint8[] list must hold integers from 0 to 255")
        return bytes(items)
    if isinstance(value, str) and info.mode == "python":
        # The same text as JSON mode takes (so the schema's pattern is the truth in both modes)
        if not _BASE64.fullmatch(value):
            raise ValueError("uint8[] given as a string must be base64 (one alphabet, at most its padding)")
        try:
            text = value.rstrip("=").replace("-", "+").replace("_", "/")
            return base64.b64decode(text + "=" * (-len(text) % 4), validate=True)
        except binascii.Error as error:
            raise ValueError(f"uint8[] given as a string must be base64 ({error})") from None
    return value


def _bytes_to_base64(value: bytes) -> str:
    # The standard alphabet (pydantic's "base64" writes the URL-safe one), so a browser can put
    # a JPEG straight into `data:image/jpeg;base64,...` as rosbridge clients do.
    return base64.b64encode(value).decode("ascii")


# uint8[] and byte[] as Python bytes; base64 text in JSON (a JSON array of ints would be 3-4x
# bigger). A model with such a field also sets ser_json_bytes/val_json_bytes="base64" in its config.
_Base64Bytes = Annotated[
    bytes,
    BeforeValidator(_bytes_from),
    PlainSerializer(_bytes_to_base64, return_type=str, when_used="json"),
    WithJsonSchema(
        {
            "anyOf": [
                {"type": "string", "contentEncoding": "base64", "pattern": _BASE64.pattern},
                {"type": "array", "items": {"type": "integer", "minimum": 0, "maximum": 255}},
            ],
            "description": "bytes as base64 (written with the standard alphabet), or a list of integers 0-255",
        }
    ),
]
Base64Bytes = _Base64Bytes  # for a byte array of another size: Annotated[Base64Bytes, RosPrimitive("uint8[16]")]
UInt8Array = Annotated[_Base64Bytes, RosPrimitive("uint8[]")]
ByteArray = Annotated[_Base64Bytes, RosPrimitive("byte[]")]


def fixed_floats(length: int) -> Any:
    """The field of a fixed-size float array (``float64[36] covariance``): ``length`` zeros by
    default, and any other length refused. Use as ``covariance: list[Float64] = fixed_floats(36)``.
    """
    return Field(default_factory=lambda: [0.0] * length, min_length=length, max_length=length)


# Every registered interface by its full ROS name ("pkg/msg/Name", "pkg/srv/Name", "pkg/action/Name").
_INTERFACES: dict[str, type[Message] | type[ServiceType] | type[ActionType]] = {}


def _register(ros_type: str, cls: type[Message] | type[ServiceType] | type[ActionType]) -> None:
    existing = _INTERFACES.get(ros_type)
    if existing is not None and existing is not cls:
        raise TypeError(f"interface {ros_type} is defined twice ({existing!r} and {cls!r})")
    _INTERFACES[ros_type] = cls


def forget_interfaces(names: Iterable[str]) -> None:
    """Unregister ``names`` (the definition loader undoes a build that failed half-way, so the
    fixed file can be built again)."""
    for name in names:
        _INTERFACES.pop(name, None)


def registered(prefix: str = "") -> dict[str, type[Message] | type[ServiceType] | type[ActionType]]:
    """The types registered so far whose name starts with ``prefix`` (``"std_srvs/srv/"``),
    without loading the catalogue: a package's view needs only its own module."""
    return {name: cls for name, cls in _INTERFACES.items() if name.startswith(prefix)}


class Message(BaseModel):
    """Base class of every message; subclasses set ``__ros_type__`` to register themselves.

    Non-finite floats are refused everywhere (JSON cannot carry them and no Skydeck position,
    setpoint or rate means anything as NaN), and unknown fields are refused so a typo in a
    published frame is reported instead of silently dropped. Assignments are validated too, as
    rclpy's field setters check theirs: ``msg.linear.x = float("nan")`` fails on that line, in
    the user's code, instead of as a ``null`` that every reader refuses (a list appended in
    place is checked where it is next validated, by the reader).
    """

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, validate_assignment=True)

    __ros_type__: ClassVar[str] = ""
    # The comment block `interface show` prints above the fields, as in the .msg file.
    __ros_comment__: ClassVar[str] = ""
    # Named constants of the .msg file (`uint8 FRAME_LOCAL_NED=1`), printed by `interface show`.
    __ros_constants__: ClassVar[tuple[str, ...]] = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.__dict__.get("__ros_type__"):
            _register(cls.__ros_type__, cls)

    def __init__(self, /, *args: Any, **data: Any) -> None:
        """Keywords as ROS 2 (``Point(x=1.0)``), or positional values in field order as ROS 1
        (``Point(1.0, 2.0, 3.0)``); fields left out keep their defaults."""
        if args:
            data = self._positional(args, data)
        self.__pydantic_validator__.validate_python(data, self_instance=self)

    # Pydantic calls a model's own __init__ for every nested dict it validates when the class
    # overrides it; this one adds nothing there (positional values come only from Python
    # calls), so the flag keeps model_validate_json on pydantic's fast path.
    __init__.__pydantic_base_init__ = True  # type: ignore[attr-defined]

    def __repr__(self) -> str:
        """As rclpy prints a message: ``geometry_msgs.msg.Point(x=1.0, y=2.0, z=0.0)``."""
        name = self.__ros_type__.replace("/", ".") if self.__ros_type__ else type(self).__name__
        fields = ", ".join(f"{field}={getattr(self, field)!r}" for field in type(self).__pydantic_fields__)
        return f"{name}({fields})"

    __str__ = __repr__  # print(msg) shows the same, as in ROS 2 (pydantic's str drops the type)

    @classmethod
    def _positional(cls, args: tuple[Any, ...], data: dict[str, Any]) -> dict[str, Any]:
        """The keyword form of a positional call, refused as genpy refuses it."""
        names = tuple(cls.__pydantic_fields__)
        if data:
            raise TypeError(
                f"{cls.__name__}() takes positional or keyword arguments, not both (as ROS 1 "
                f"messages): got {len(args)} positional and {', '.join(data)}"
            )
        if len(args) > len(names):
            fields = f" ({', '.join(names)})" if names else ""
            plural = "" if len(names) == 1 else "s"
            raise TypeError(
                f"{cls.__name__}() takes at most {len(names)} positional argument{plural}"
                f"{fields}, {len(args)} given"
            )
        return dict(zip(names, args, strict=False))


class ServiceType:
    """A ROS service: a ``Request`` and a ``Response`` message under one name.

    Subclasses set ``__ros_type__`` (``"std_srvs/srv/Trigger"``), ``Request`` and ``Response``;
    rclpy's ``Trigger.Request()`` and rospy's ``TriggerResponse()`` both read the same.
    """

    __ros_type__: ClassVar[str] = ""
    __ros_comment__: ClassVar[str] = ""
    Request: ClassVar[type[Message]]
    Response: ClassVar[type[Message]]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.__dict__.get("__ros_type__"):
            for part in ("Request", "Response"):
                if not (isinstance(getattr(cls, part, None), type) and issubclass(getattr(cls, part), Message)):
                    raise TypeError(f"service {cls.__ros_type__} needs a {part} message class")
            _register(cls.__ros_type__, cls)


class ActionType:
    """A ROS action: ``Goal``, ``Result`` and ``Feedback`` messages under one name, and the
    types ROS 2 derives from them to carry an action over services and topics.

    Subclasses set ``__ros_type__`` (``"example_interfaces/action/Fibonacci"``) and the six
    parts: ``Goal``, ``Result``, ``Feedback`` (messages), ``SendGoal`` and ``GetResult``
    (services), ``FeedbackMessage`` (a message). ``Impl`` holds them under rclpy's names
    (``Fibonacci.Impl.SendGoalService``), with the action_msgs types every action shares.
    """

    __ros_type__: ClassVar[str] = ""
    __ros_comment__: ClassVar[str] = ""
    Goal: ClassVar[type[Message]]
    Result: ClassVar[type[Message]]
    Feedback: ClassVar[type[Message]]
    SendGoal: ClassVar[type[ServiceType]]
    GetResult: ClassVar[type[ServiceType]]
    FeedbackMessage: ClassVar[type[Message]]
    Impl: ClassVar[type]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.__dict__.get("__ros_type__"):
            parts = {"Goal": Message, "Result": Message, "Feedback": Message, "SendGoal": ServiceType,
                     "GetResult": ServiceType, "FeedbackMessage": Message}  # fmt: skip
            for part, base in parts.items():
                if not (isinstance(getattr(cls, part, None), type) and issubclass(getattr(cls, part), base)):
                    raise TypeError(f"action {cls.__ros_type__} needs a {part} {base.__name__} class")
            _register(cls.__ros_type__, cls)
