"""CDR, the encoding of ROS 2 messages on DDS and in rosbag2's files, for Skydeck's types.

Written from OMG's CDR rules as ROS 2 applies them (XCDR1, "plain" CDR, little endian):

- a 4-byte encapsulation header, ``00 01 00 00`` (CDR_LE), then the fields in order;
- each primitive aligned to its own size (8 for float64/int64/uint64), counted from the end of
  the header; bool, byte, char, int8 and uint8 take one byte;
- a string is a uint32 length that counts its NUL, the UTF-8 bytes, then the NUL;
- a sequence (``T[]``, ``T[<=N]``) is a uint32 count, then the items; a fixed array (``T[N]``)
  is the N items alone;
- a message with no fields is one zero byte (rosidl gives it a ``uint8`` member).

Values are what JSON gives: a message is a dict (a missing field is its zero, so a frame without
a default-valued field still encodes), ``uint8[]``/``byte[]`` is ``bytes`` (base64 text and lists
of ints are taken too), other arrays are lists. :meth:`CdrCodec.decode` gives the same shapes
back, byte arrays as ``bytes``. Each type is compiled once into a pair of Python functions (one
``struct`` call per run of same-sized numbers), so a message is encoded without a walk over a
generic description.

Example::

    codec = codec_of(Point)
    data = codec.encode({"x": 1.0, "y": 2.0, "z": 0.0})   # b'\\x00\\x01\\x00\\x00...'
    codec.decode(data)                                      # {'x': 1.0, 'y': 2.0, 'z': 0.0}
"""

from __future__ import annotations

import base64
import binascii
import json
import struct
from collections.abc import Callable, Mapping
from functools import cache
from typing import Any

from shared_models._message import Message
from shared_models.errors import SkydeckError
from shared_models.ros2msg import FieldSpec, MessageSpec, specs_of

__all__ = ["ENCAPSULATION", "CdrCodec", "CdrError", "codec_for", "codec_of", "json_frame", "keeper"]

ENCAPSULATION = b"\x00\x01\x00\x00"  # CDR_LE, no options

# primitive -> (struct code, size)
_CODES = {
    "bool": ("?", 1), "byte": ("B", 1), "char": ("B", 1), "int8": ("b", 1), "uint8": ("B", 1),
    "int16": ("h", 2), "uint16": ("H", 2), "int32": ("i", 4), "uint32": ("I", 4),
    "int64": ("q", 8), "uint64": ("Q", 8), "float32": ("f", 4), "float64": ("d", 8),
}
_ZEROS = {"bool": "False", "float32": "0.0", "float64": "0.0", "string": "''", "wstring": "''"}
_BYTES = ("uint8", "byte", "char")
_PAD = tuple(bytes(n) for n in range(8))


class CdrError(SkydeckError, ValueError):
    """A value that does not fit its type's CDR, or bytes that are not a message of the type."""


def _as_bytes(value: Any) -> bytes:
    if isinstance(value, bytes | bytearray | memoryview):
        return bytes(value)
    if isinstance(value, str):
        try:
            return base64.b64decode(value, validate=True)
        except binascii.Error:
            raise CdrError("a byte array given as text must be base64") from None
    return bytes(value)  # a list of ints 0-255


class CdrCodec:
    """Encodes and decodes one message type (see the module docstring)."""

    def __init__(self, name: str, encode: Callable[[Any, bytearray], None], decode: Callable[[bytes, int], Any]) -> None:
        self.name = name
        self._encode = encode
        self._decode = decode

    def encode(self, value: Mapping[str, Any]) -> bytes:
        """The CDR bytes of ``value`` (a dict of the type's fields), header included."""
        buffer = bytearray(ENCAPSULATION)
        try:
            self._encode(value, buffer)
        except CdrError as error:
            raise CdrError(f"{self.name}: {error}") from None
        except (struct.error, TypeError, ValueError, AttributeError, OverflowError) as error:
            raise CdrError(f"{self.name}: cannot encode {_short(value)}: {error}") from None
        return bytes(buffer)

    def decode(self, data: bytes | bytearray | memoryview) -> dict[str, Any]:
        """The fields of the message in ``data`` (CDR with its 4-byte header)."""
        data = bytes(data)
        if data[:2] != ENCAPSULATION[:2]:
            kind = data[:2].hex() or "nothing"
            raise CdrError(
                f"{self.name}: not little-endian plain CDR (the header says {kind}, expected 0001)"
            )
        try:
            value, _ = self._decode(data, 4)
        except (struct.error, UnicodeDecodeError, IndexError) as error:
            raise CdrError(f"{self.name}: {len(data)} bytes are not one message of this type ({error})") from None
        return value  # type: ignore[no-any-return]


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


@cache
def codec_of(cls: type[Message]) -> CdrCodec:
    """The codec of a Skydeck message type (its ROS 2 view: see :mod:`shared_models.ros2msg`)."""
    return codec_for(cls.__ros_type__, specs_of(cls))


def codec_for(name: str, specs: Mapping[str, MessageSpec]) -> CdrCodec:
    """The codec of ``name``, given the specs of it and every type it uses."""
    compiler = _Compiler(specs)
    encode, decode = compiler.compile(name)
    return CdrCodec(name, encode, decode)


class _Compiler:
    """Writes the Python source of each type's two functions and compiles them together."""

    def __init__(self, specs: Mapping[str, MessageSpec]) -> None:
        self.specs = specs
        self.names: dict[str, int] = {}
        self.source: list[str] = []
        self.namespace: dict[str, Any] = {
            "_PAD": _PAD, "_as_bytes": _as_bytes, "_pack": struct.pack, "_unpack": struct.unpack_from,
            "CdrError": CdrError,
        }

    def compile(self, name: str) -> tuple[Callable[[Any, bytearray], None], Callable[[bytes, int], Any]]:
        number = self._add(name)
        exec(compile("\n".join(self.source), f"<cdr {name}>", "exec"), self.namespace)  # noqa: S102
        return self.namespace[f"_e{number}"], self.namespace[f"_d{number}"]

    def _add(self, name: str) -> int:
        if name in self.names:
            return self.names[name]
        spec = self.specs.get(name)
        if spec is None:
            raise CdrError(f"no definition of {name}")
        number = self.names[name] = len(self.names)
        for item in spec.fields:
            if not item.is_primitive:
                self._add(item.type)
        self.source += self._encoder(number, spec) + self._decoder(number, spec)
        return number

    # -- encoding ---------------------------------------------------------------------------------

    def _encoder(self, number: int, spec: MessageSpec) -> list[str]:
        lines = [f"def _e{number}(v, b):", "    g = v.get"]
        if not spec.fields:
            lines.append("    b += b'\\x00'")
        for run in _runs(spec.fields):
            lines += ["    " + line for line in self._encode_run(run)]
        return lines

    def _encode_run(self, run: list[FieldSpec]) -> list[str]:
        first = run[0]
        if len(run) > 1 or (first.is_primitive and first.type in _CODES and first.array is None):
            code, size = _CODES[first.type]
            values = ", ".join(f"g({f.name!r}, {_ZEROS.get(f.type, '0')})" for f in run)
            return _align(size) + [f"b += _pack('<{len(run)}{code}', {values})"]
        return self._encode_field(first)

    def _encode_field(self, item: FieldSpec) -> list[str]:
        get = f"g({item.name!r}, {_ZEROS.get(item.type, '0') if item.array is None else '()'})"
        if item.array is None:
            if item.type in ("string", "wstring"):
                return _encode_string(get)
            return [f"_e{self._add(item.type)}(g({item.name!r}, {{}}), b)"]
        fixed = item.array >= 0 and not item.bounded
        if item.type in _BYTES:
            lines = [f"a = _as_bytes({get})"]
            unit = "bytes"
        else:
            lines = [f"a = {get}"]
            unit = "items"
        if fixed:
            lines.append(f"if len(a) != {item.array}: raise CdrError('{item.name} must have {item.array} {unit}, not %d' % len(a))")
        else:
            if item.bounded:
                lines.append(f"if len(a) > {item.array}: raise CdrError('{item.name} may have at most {item.array} {unit}, not %d' % len(a))")
            lines += _align(4) + ["b += _pack('<I', len(a))"]
        if item.type in _BYTES:
            return [*lines, "b += a"]
        if item.type in _CODES:
            code, size = _CODES[item.type]
            return lines + ["if a:", *["    " + line for line in _align(size)], f"    b += _pack('<%d{code}' % len(a), *a)"]
        if item.type in ("string", "wstring"):
            return lines + ["for s in a:", *["    " + line for line in _encode_string("s")]]
        return lines + [f"for m in a: _e{self._add(item.type)}(m, b)"]

    # -- decoding ---------------------------------------------------------------------------------

    def _decoder(self, number: int, spec: MessageSpec) -> list[str]:
        lines = [f"def _d{number}(d, o):", "    v = {}"]
        if not spec.fields:
            lines.append("    o += 1")
        for run in _runs(spec.fields):
            lines += ["    " + line for line in self._decode_run(run)]
        return [*lines, "    return v, o"]

    def _decode_run(self, run: list[FieldSpec]) -> list[str]:
        first = run[0]
        if len(run) > 1 or (first.is_primitive and first.type in _CODES and first.array is None):
            code, size = _CODES[first.type]
            targets = ", ".join(f"v[{f.name!r}]" for f in run) + ("," if len(run) == 1 else "")
            return _align_read(size) + [f"{targets} = _unpack('<{len(run)}{code}', d, o)", f"o += {size * len(run)}"]
        return self._decode_field(first)

    def _decode_field(self, item: FieldSpec) -> list[str]:
        target = f"v[{item.name!r}]"
        if item.array is None:
            if item.type in ("string", "wstring"):
                return [*_decode_string("s"), f"{target} = s"]
            return [f"{target}, o = _d{self._add(item.type)}(d, o)"]
        if item.array >= 0 and not item.bounded:
            lines = [f"n = {item.array}"]
        else:
            lines = [*_align_read(4), "n, = _unpack('<I', d, o)", "o += 4"]
            if item.bounded:
                lines += [f"if n > {item.array}: raise CdrError('{item.name} holds %d items, more than its bound {item.array}' % n)"]
        if item.type in _BYTES:
            return lines + ["if o + n > len(d): raise IndexError('the byte array runs past the end')",
                            f"{target} = d[o:o + n]", "o += n"]
        if item.type in _CODES:
            code, size = _CODES[item.type]
            return lines + [f"{target} = []", "if n:", *["    " + line for line in _align_read(size)],
                            f"    {target} = list(_unpack('<%d{code}' % n, d, o))", f"    o += n * {size}"]
        if item.type in ("string", "wstring"):
            return lines + ["a = []", "for _ in range(n):", *["    " + line for line in _decode_string("s")],
                            "    a.append(s)", f"{target} = a"]
        return lines + ["a = []", "for _ in range(n):", f"    m, o = _d{self._add(item.type)}(d, o)",
                        "    a.append(m)", f"{target} = a"]


def _runs(fields: tuple[FieldSpec, ...]) -> list[list[FieldSpec]]:
    """Fields grouped so that consecutive numbers of one size are packed together."""
    runs: list[list[FieldSpec]] = []
    for item in fields:
        scalar = item.array is None and item.type in _CODES
        if scalar and runs and _scalar_run(runs[-1]) and _CODES[runs[-1][0].type] == _CODES[item.type]:
            runs[-1].append(item)
        else:
            runs.append([item])
    return runs


def _scalar_run(run: list[FieldSpec]) -> bool:
    return run[0].array is None and run[0].type in _CODES


def _align(size: int) -> list[str]:
    # The payload starts after the 4-byte header: alignment counts from there.
    return [] if size == 1 else [f"b += _PAD[(4 - len(b)) % {size}]"]


def _align_read(size: int) -> list[str]:
    return [] if size == 1 else [f"o += (4 - o) % {size}"]


def _encode_string(value: str) -> list[str]:
    return [f"t = {value}.encode()", *_align(4), "b += _pack('<I', len(t) + 1)", "b += t", "b += b'\\x00'"]


def _decode_string(target: str) -> list[str]:
    # A length of 0 (no NUL at all) is what some writers send for an empty string.
    return [*_align_read(4), "n, = _unpack('<I', d, o)", "o += 4",
            f"{target} = d[o:o + n - 1].decode() if n else ''", "o += n",
            "if o > len(d): raise IndexError('a string runs past the end')"]


# -- from a decoded message to a Skydeck frame --------------------------------------------------


def _shape(specs: Mapping[str, MessageSpec], name: str) -> Any:
    """A type's fields, names and kinds, nested types written out (their names apart)."""
    return tuple(
        (f.name, f.type if f.is_primitive else _shape(specs, f.type), f.array, f.bounded) for f in specs[name].fields
    )


def keeper(
    theirs: Mapping[str, MessageSpec], their_name: str, cls: type[Message]
) -> Callable[[dict[str, Any]], dict[str, Any]] | None:
    """What keeps, of a message decoded with another definition of ``cls`` (a newer ROS 2's, a
    recording's), the fields ``cls`` has; None when the two definitions are the same."""
    ours = specs_of(cls)
    if _shape(theirs, their_name) == _shape(ours, cls.__ros_type__):
        return None

    def keep(value: dict[str, Any], type_name: str = cls.__ros_type__) -> dict[str, Any]:
        out = {}
        for item in ours[type_name].fields:
            if item.name not in value:
                continue
            field = value[item.name]
            if not item.is_primitive:
                field = [keep(v, item.type) for v in field] if item.array is not None else keep(field, item.type)
            out[item.name] = field
        return out

    return keep


def _json_default(value: Any) -> Any:
    if isinstance(value, bytes | bytearray):
        return base64.b64encode(value).decode("ascii")
    raise TypeError(f"cannot write {type(value).__name__} as JSON")


def json_frame(value: Mapping[str, Any]) -> str:
    """The Skydeck frame (JSON text, byte arrays as base64) of a decoded message; ValueError for
    NaN or infinity, which Skydeck's messages refuse (JSON cannot carry them)."""
    return json.dumps(value, default=_json_default, allow_nan=False, separators=(",", ":"))
