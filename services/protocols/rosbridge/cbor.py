"""CBOR (RFC 8949) as rosbridge's ``cbor`` and ``cbor-raw`` compressions send it, written here.

Only what a rosbridge message holds, written out in full: maps with text keys, arrays, text,
byte strings, integers, float64, booleans, null, and tags. As rosbridge_suite writes a message
(its ``cbor_conversion``), an array of numbers goes as one typed array (RFC 8746: a tag over
the little-endian bytes, which roslibjs's decoder turns into a ``Float32Array``...), and
``uint8[]``/``byte[]``/``char[]`` as a plain byte string.

    to_cbor = message_values(PoseStamped)      # compiled once per type
    dumps({"op": "publish", "topic": "/pose", "msg": to_cbor(json.loads(frame))})
"""

from __future__ import annotations

import base64
import struct
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from typing import Any

from shared_models import Message
from shared_models.ros2msg import MessageSpec, specs_of

__all__ = ["Tag", "dumps", "message_values"]


@dataclass(frozen=True)
class Tag:
    """A tagged item: ``tag`` (a number) over ``value``."""

    tag: int
    value: Any


# RFC 8746's tags for little-endian typed arrays, and struct's code for one item
_TYPED_ARRAYS = {
    "uint16": (69, "H"), "uint32": (70, "I"), "uint64": (71, "Q"),
    "int8": (72, "b"), "int16": (77, "h"), "int32": (78, "i"), "int64": (79, "q"),
    "float32": (85, "f"), "float64": (86, "d"),
}  # fmt: skip
_BYTES = ("uint8", "byte", "char")


def dumps(value: Any) -> bytes:
    """``value`` as CBOR bytes."""
    out = bytearray()
    _write(out, value)
    return bytes(out)


def _head(out: bytearray, major: int, number: int) -> None:
    kind = major << 5
    if number < 24:
        out.append(kind | number)
    elif number < 0x100:
        out += bytes((kind | 24, number))
    elif number < 0x10000:
        out.append(kind | 25)
        out += number.to_bytes(2, "big")
    elif number < 0x100000000:
        out.append(kind | 26)
        out += number.to_bytes(4, "big")
    else:
        out.append(kind | 27)
        out += number.to_bytes(8, "big")


def _write(out: bytearray, value: Any) -> None:
    if value is None:
        out.append(0xF6)
    elif value is True:
        out.append(0xF5)
    elif value is False:
        out.append(0xF4)
    elif isinstance(value, int):
        if value >= 0:
            _head(out, 0, value)
        else:
            _head(out, 1, -1 - value)
    elif isinstance(value, float):
        out.append(0xFB)
        out += struct.pack(">d", value)
    elif isinstance(value, str):
        data = value.encode()
        _head(out, 3, len(data))
        out += data
    elif isinstance(value, bytes | bytearray):
        _head(out, 2, len(value))
        out += value
    elif isinstance(value, dict):
        _head(out, 5, len(value))
        for key, item in value.items():
            _write(out, key)
            _write(out, item)
    elif isinstance(value, list | tuple):
        _head(out, 4, len(value))
        for item in value:
            _write(out, item)
    elif isinstance(value, Tag):
        _head(out, 6, value.tag)
        _write(out, value.value)
    else:
        raise TypeError(f"CBOR cannot carry {type(value).__name__}")


# -- a message's values, typed as rosbridge sends them -----------------------------------------

Convert = Callable[[Any], Any]


def message_values(cls: type[Message]) -> Convert:
    """A function from a message of ``cls`` as JSON gives it (``json.loads`` of its frame) to
    the values CBOR carries: typed arrays for numbers, byte strings for bytes."""
    return _compiled(cls.__ros_type__, cls)


@cache
def _compiled(name: str, cls: type[Message]) -> Convert:
    specs = specs_of(cls)
    converters: dict[str, Convert] = {}

    def build(spec_name: str) -> Convert:
        found = converters.get(spec_name)
        if found is not None:
            return found
        spec: MessageSpec = specs[spec_name]
        fields: list[tuple[str, Convert | None]] = []
        for field in spec.fields:
            if field.is_primitive:
                fields.append((field.name, _primitive_array(field.type) if field.array is not None else None))
            else:
                nested = build(field.type)
                fields.append((field.name, nested if field.array is None else _each(nested)))

        def convert(value: Any) -> Any:
            if not isinstance(value, dict):
                return value
            out = dict(value)
            for field_name, change in fields:
                if change is not None and field_name in out:
                    out[field_name] = change(out[field_name])
            return out

        converters[spec_name] = convert
        return convert

    return build(name)


def _each(convert: Convert) -> Convert:
    return lambda items: [convert(item) for item in items] if isinstance(items, list) else items


def _primitive_array(kind: str) -> Convert | None:
    if kind in _BYTES:
        return _as_bytes
    typed = _TYPED_ARRAYS.get(kind)
    if typed is None:  # bool[], string[]: a CBOR array of items
        return None
    tag, code = typed

    def pack(items: Any) -> Any:
        if not isinstance(items, list):
            return items
        return Tag(tag, struct.pack(f"<{len(items)}{code}", *items))

    return pack


def _as_bytes(value: Any) -> Any:
    """``uint8[]`` as JSON gives it (base64 text, or a list of ints) as bytes."""
    if isinstance(value, str):
        return base64.b64decode(value + "=" * (-len(value) % 4))
    if isinstance(value, list):
        return bytes(value)
    return value
