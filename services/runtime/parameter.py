"""One parameter value, as ``rclpy.parameter``: :class:`Parameter` (a name, a
``Parameter.Type`` and a plain Python value) and its conversions to and from
``rcl_interfaces/msg/Parameter`` and ``ParameterValue``.

    Parameter("speed", Parameter.Type.DOUBLE, 0.5)
    Parameter("speed", value=0.5).to_parameter_msg()

What a node does with them (declaring, checking, callbacks) is :mod:`services.runtime.parameters`.
"""

from __future__ import annotations

import math
from enum import IntEnum
from typing import Any

from shared_models.rcl_interfaces import Parameter as ParameterMsg
from shared_models.rcl_interfaces import ParameterValue

__all__ = ["Parameter", "ParameterValueType", "parameter_value_to_python"]

# The integers JSON carries exactly (JavaScript's safe integers): rcl_interfaces' integer fields
# are bounded so in Skydeck, for every client to read them alike.
_INT_RANGE = (-(2**53 - 1), 2**53 - 1)


class ParameterValueType(IntEnum):
    """The parameter types (``Parameter.Type``), numbered as ``rcl_interfaces/msg/ParameterType``."""

    NOT_SET = 0
    BOOL = 1
    INTEGER = 2
    DOUBLE = 3
    STRING = 4
    BYTE_ARRAY = 5
    BOOL_ARRAY = 6
    INTEGER_ARRAY = 7
    DOUBLE_ARRAY = 8
    STRING_ARRAY = 9

    @classmethod
    def from_parameter_value(cls, value: Any) -> ParameterValueType:
        """The type of a Python value; TypeError for a value no parameter can hold.

        An empty list is a BYTE_ARRAY, as in rclpy; a parameter declared with one takes the
        type of the first non-empty list it is given (see :meth:`NodeParameters.declare`).
        """
        if value is None:
            return cls.NOT_SET
        scalar = _scalar_type(value)
        if scalar is not None:
            return scalar
        if isinstance(value, bytes | bytearray):
            return cls.BYTE_ARRAY
        if isinstance(value, list | tuple):
            kinds = {_scalar_type(item) if not isinstance(item, bytes) else cls.BYTE_ARRAY for item in value}
            if not kinds or kinds == {cls.BYTE_ARRAY}:
                return cls.BYTE_ARRAY
            if len(kinds) == 1 and (kind := next(iter(kinds))) in _ARRAY_OF:
                return _ARRAY_OF[kind]
            if kinds == {cls.INTEGER, cls.DOUBLE}:  # [1, 2.5] is a list of numbers: doubles
                return cls.DOUBLE_ARRAY
        raise TypeError(
            f"{value!r} is not a parameter value: a bool, int, float, str, bytes, "
            "or a list of bools, ints, floats or strings (all of one type)"
        )

    def check(self, value: Any) -> bool:
        """Whether ``value`` is of this type (an empty list fits every array type)."""
        if self is ParameterValueType.NOT_SET:
            return value is None
        try:
            found = ParameterValueType.from_parameter_value(value)
        except TypeError:
            return False
        return found is self or (self.is_array and isinstance(value, list | tuple) and not value)

    @property
    def is_array(self) -> bool:
        return self >= ParameterValueType.BYTE_ARRAY

    @property
    def label(self) -> str:
        """How ``ros2 param`` names it: ``double``, ``string array``..."""
        return _LABELS[self]




def _scalar_type(value: Any) -> ParameterValueType | None:
    if isinstance(value, bool):  # before int: a bool is an int in Python
        return ParameterValueType.BOOL
    if isinstance(value, int):
        return ParameterValueType.INTEGER
    if isinstance(value, float):
        return ParameterValueType.DOUBLE
    if isinstance(value, str):
        return ParameterValueType.STRING
    return None


_ARRAY_OF = {
    ParameterValueType.BOOL: ParameterValueType.BOOL_ARRAY,
    ParameterValueType.INTEGER: ParameterValueType.INTEGER_ARRAY,
    ParameterValueType.DOUBLE: ParameterValueType.DOUBLE_ARRAY,
    ParameterValueType.STRING: ParameterValueType.STRING_ARRAY,
}
_LABELS = {
    ParameterValueType.NOT_SET: "not set",
    ParameterValueType.BOOL: "boolean",
    ParameterValueType.INTEGER: "integer",
    ParameterValueType.DOUBLE: "double",
    ParameterValueType.STRING: "string",
    ParameterValueType.BYTE_ARRAY: "byte array",
    ParameterValueType.BOOL_ARRAY: "boolean array",
    ParameterValueType.INTEGER_ARRAY: "integer array",
    ParameterValueType.DOUBLE_ARRAY: "double array",
    ParameterValueType.STRING_ARRAY: "string array",
}
# The field of rcl_interfaces/msg/ParameterValue that holds each type.
_FIELD = {
    ParameterValueType.BOOL: "bool_value",
    ParameterValueType.INTEGER: "integer_value",
    ParameterValueType.DOUBLE: "double_value",
    ParameterValueType.STRING: "string_value",
    ParameterValueType.BYTE_ARRAY: "byte_array_value",
    ParameterValueType.BOOL_ARRAY: "bool_array_value",
    ParameterValueType.INTEGER_ARRAY: "integer_array_value",
    ParameterValueType.DOUBLE_ARRAY: "double_array_value",
    ParameterValueType.STRING_ARRAY: "string_array_value",
}


class Parameter:
    """A named, typed value, as ``rclpy.parameter.Parameter``::

        Parameter("speed", Parameter.Type.DOUBLE, 0.5)
        Parameter("speed", value=0.5)          # the type from the value

    Values are kept as plain Python: bool, int, float, str, ``bytes`` for BYTE_ARRAY, lists for
    the other arrays. A wrong value for the type is a ValueError; a value of no parameter type a
    TypeError (both as rclpy).
    """

    Type = ParameterValueType

    __slots__ = ("_name", "_type", "_value")

    def __init__(self, name: str, type_: ParameterValueType | None = None, value: Any = None) -> None:
        if type_ is None:
            type_ = ParameterValueType.from_parameter_value(value)
        type_ = ParameterValueType(type_)
        if not type_.check(value):
            raise ValueError(f"type {type_.name} and value {value!r} of parameter {name!r} do not agree")
        self._name = name
        self._type = type_
        self._value = _normalised(type_, value)

    @property
    def name(self) -> str:
        return self._name

    @property
    def type_(self) -> ParameterValueType:
        return self._type

    @property
    def value(self) -> Any:
        return self._value

    def get_parameter_value(self) -> ParameterValue:
        """This value as an ``rcl_interfaces/msg/ParameterValue``."""
        if self._type is ParameterValueType.NOT_SET:
            return ParameterValue()
        value = self._value
        if self._type is ParameterValueType.BYTE_ARRAY and isinstance(value, list):
            value = b"".join(value)
        return ParameterValue.model_validate({"type": int(self._type), _FIELD[self._type]: value})

    def to_parameter_msg(self) -> ParameterMsg:
        """This parameter as an ``rcl_interfaces/msg/Parameter``."""
        return ParameterMsg(name=self._name, value=self.get_parameter_value())

    @classmethod
    def from_parameter_msg(cls, msg: ParameterMsg) -> Parameter:
        """A parameter from an ``rcl_interfaces/msg/Parameter``; ValueError for an unknown type."""
        return cls(msg.name, _type_of_msg(msg.value), parameter_value_to_python(msg.value))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Parameter):
            return NotImplemented
        return (self._name, self._type, self._value) == (other._name, other._type, other._value)

    def __hash__(self) -> int:
        return hash((self._name, self._type))

    def __repr__(self) -> str:
        return f"Parameter({self._name!r}, Parameter.Type.{self._type.name}, {self._value!r})"


def _normalised(type_: ParameterValueType, value: Any) -> Any:
    """One Python form per type: ``bytes`` for byte arrays, lists for arrays, checked numbers."""
    if isinstance(value, list | tuple) and not value:
        return []  # an empty list stays one, whatever array type it is taken as
    if type_ is ParameterValueType.BYTE_ARRAY:
        return b"".join(value) if isinstance(value, list | tuple) else bytes(value)
    if type_ is ParameterValueType.DOUBLE_ARRAY:
        value = [float(item) for item in value]
    elif type_.is_array:
        value = list(value)
    numbers = value if isinstance(value, list) else [value]
    if type_ in (ParameterValueType.INTEGER, ParameterValueType.INTEGER_ARRAY) and any(not _INT_RANGE[0] <= n <= _INT_RANGE[1] for n in numbers):
        raise ValueError(f"{value!r} is out of the integer range JSON carries exactly (+-2**53 - 1)")
    if type_ in (ParameterValueType.DOUBLE, ParameterValueType.DOUBLE_ARRAY) and not all(math.isfinite(n) for n in numbers):
        raise ValueError(f"{value!r} is not finite (JSON cannot carry NaN or infinity)")
    return value


def _type_of_msg(value: ParameterValue) -> ParameterValueType:
    try:
        return ParameterValueType(value.type)
    except ValueError:
        raise ValueError(f"{value.type} is not a ParameterType (0-9)") from None


def parameter_value_to_python(value: ParameterValue) -> Any:
    """The Python value an ``rcl_interfaces/msg/ParameterValue`` holds (None when NOT_SET)."""
    type_ = _type_of_msg(value)
    if type_ is ParameterValueType.NOT_SET:
        return None
    return getattr(value, _FIELD[type_])
