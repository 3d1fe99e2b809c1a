"""Reading ``.msg``, ``.srv`` and ``.action`` files, in ROS 1's syntax and ROS 2's.

    int32 X=5                   a constant (ROS 1 also ``int32 X = 5``; ``string S=text to the end``)
    string S="a"                a string constant, quoted (ROS 2)
    float64 speed 0.5           a field with a default (ROS 2)
    int32[] a [1, 2]            an array with a default
    int32[<=5] b                a bounded array; ``int32[3] c`` a fixed one
    string<=10 name             a bounded string
    geometry_msgs/Point p       a message of another package (``geometry_msgs/msg/Point`` too)
    Status s                    a message of the same package
    time t / duration d         ROS 1's builtin_interfaces/Time and Duration
    Header header               ROS 1's std_msgs/Header
    ---                         between a service's request and response, an action's goal,
                                result and feedback

The result is plain data (:class:`Definition`), turned into message classes by
:mod:`shared_models.definitions.builder`. A line that cannot be read is a
:class:`~shared_models.definitions.errors.DefinitionError` naming the file and line.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass
from typing import Any

from shared_models.definitions.errors import DefinitionError

__all__ = [
    "KINDS",
    "PRIMITIVES",
    "ConstantSpec",
    "Definition",
    "FieldSpec",
    "FieldType",
    "MessageSpec",
    "parse_definition",
]

KINDS = {"msg": 1, "srv": 2, "action": 3}
"""Each kind of file and how many messages it declares (parts between ``---`` lines)."""

_INTEGERS = {
    "byte": (0, 0xFF),
    "char": (0, 0xFF),
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 0xFF),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 0xFFFF),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
_FLOATS = ("float32", "float64")
_STRINGS = ("string", "wstring")
PRIMITIVES = ("bool", *_INTEGERS, *_FLOATS, *_STRINGS)
"""The primitive types of ROS 2 (ROS 1's are the same names, with ``time`` and ``duration``)."""

# ROS 1's names for types that are messages in ROS 2.
_ROS1_ALIASES = {
    "time": "builtin_interfaces/msg/Time",
    "duration": "builtin_interfaces/msg/Duration",
    "Header": "std_msgs/msg/Header",
}
_MAX_FIXED_SIZE = 100_000  # a fixed array's default is made in full: keep a typo from eating memory

_NAME = r"[A-Za-z][A-Za-z0-9_]*"
_CONSTANT = re.compile(rf"^(\S+)\s+({_NAME})\s*=\s*(.*)$")
_FIELD = re.compile(rf"^(\S+)\s+({_NAME})(?:\s+(.*))?$")
_TYPE = re.compile(
    r"^(?P<base>[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*){0,2})"
    r"(?:<=(?P<string_bound>\d+))?"
    r"(?:\[(?P<bounded><=)?(?P<size>\d*)\])?$"
)
_TYPE_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class FieldType:
    """A field's type: a primitive (``int32``) or a message (``geometry_msgs/msg/Point``), maybe
    a bounded string, maybe an array (``size`` None for any length; ``bounded`` for ``[<=N]``)."""

    base: str
    string_bound: int | None = None
    array: bool = False
    size: int | None = None
    bounded: bool = False

    @property
    def primitive(self) -> bool:
        return self.base in PRIMITIVES

    @property
    def fixed(self) -> bool:
        """A fixed-size array (``float64[36]``)."""
        return self.array and self.size is not None and not self.bounded

    def scalar_text(self) -> str:
        """The element's type as a definition spells it (``string<=10``)."""
        return self.base + (f"<={self.string_bound}" if self.string_bound is not None else "")

    def brackets(self) -> str:
        if not self.array:
            return ""
        if self.size is None:
            return "[]"
        return f"[<={self.size}]" if self.bounded else f"[{self.size}]"


@dataclass(frozen=True)
class FieldSpec:
    """One field: its name, type, the default the file gives (None: the type's zero), its line."""

    name: str
    type: FieldType
    default: Any = None
    line: int = 0


@dataclass(frozen=True)
class ConstantSpec:
    """One constant: ``int32 X=5``."""

    name: str
    type: str
    value: Any
    line: int = 0


@dataclass(frozen=True)
class MessageSpec:
    """One message of a file (a ``.msg``, or a part of a ``.srv`` or ``.action``)."""

    comment: str = ""
    constants: tuple[ConstantSpec, ...] = ()
    fields: tuple[FieldSpec, ...] = ()

    def signature(self) -> str:
        """What makes two versions the same type: constants and fields, never comments."""
        constants = ";".join(f"{c.type} {c.name}={c.value!r}" for c in self.constants)
        fields = ";".join(
            f"{f.type.scalar_text()}{f.type.brackets()} {f.name} {f.default!r}" for f in self.fields
        )
        return f"{constants}|{fields}"


@dataclass(frozen=True)
class Definition:
    """A parsed file: the type it declares (``my_pkg/msg/Status``), where it came from (for
    errors: ``my_pkg/msg/Status.msg``), its text as written, and its messages (1, 2 or 3)."""

    ros_type: str
    origin: str
    text: str
    parts: tuple[MessageSpec, ...]

    @property
    def package(self) -> str:
        return self.ros_type.split("/", 1)[0]

    @property
    def kind(self) -> str:
        return self.ros_type.split("/")[1]

    @property
    def name(self) -> str:
        return self.ros_type.rsplit("/", 1)[-1]

    def signature(self) -> str:
        return "---".join(part.signature() for part in self.parts)

    def dependencies(self) -> list[FieldSpec]:
        """Every field whose type is a message (the types to know before this one)."""
        return [f for part in self.parts for f in part.fields if not f.type.primitive]


def parse_definition(text: str, ros_type: str, *, origin: str | None = None) -> Definition:
    """Parse the text of the file that declares ``ros_type`` (``"my_pkg/srv/AddTwoInts"``).

    Example::

        parse_definition("int64 a\\nint64 b\\n---\\nint64 sum\\n", "my_pkg/srv/AddTwoInts")
    """
    package, kind, name = _split_type_name(ros_type, origin)
    origin = origin or f"{package}/{kind}/{name}.{kind}"
    parts: list[list[tuple[int, str]]] = [[]]
    for number, line in enumerate(text.splitlines(), start=1):
        if line.strip() == "---":
            parts.append([])
        else:
            parts[-1].append((number, line))
    if len(parts) != KINDS[kind]:
        wanted = {1: "no `---` line", 2: "one `---` line (request, then response)",
                  3: "two `---` lines (goal, result, feedback)"}[KINDS[kind]]  # fmt: skip
        raise DefinitionError(origin, None, f"a .{kind} file has {wanted}; this one has {len(parts) - 1}")
    reader = _Reader(package, origin)
    return Definition(ros_type, origin, text, tuple(reader.message(lines) for lines in parts))


def _split_type_name(ros_type: str, origin: str | None) -> tuple[str, str, str]:
    pieces = ros_type.split("/")
    if len(pieces) != 3 or pieces[1] not in KINDS or not all(_TYPE_NAME.match(p) for p in (pieces[0], pieces[2])):
        raise DefinitionError(
            origin or ros_type, None, f"{ros_type!r} is not a type name: package/msg|srv|action/Name"
        )
    return pieces[0], pieces[1], pieces[2]


class _Reader:
    """Reads the lines of one message; knows the package (bare type names are its own)."""

    def __init__(self, package: str, origin: str) -> None:
        self.package = package
        self.origin = origin

    def fail(self, line: int, problem: str) -> DefinitionError:
        return DefinitionError(self.origin, line, problem)

    def message(self, lines: list[tuple[int, str]]) -> MessageSpec:
        comment: list[str] = []
        constants: list[ConstantSpec] = []
        fields: list[FieldSpec] = []
        names: set[str] = set()
        for number, raw in lines:
            line = raw.strip()
            if not line or line.startswith("#"):
                if not constants and not fields and (line or comment):
                    comment.append(line)
                continue
            constant = _CONSTANT.match(line)
            if constant is not None:
                constants.append(self.constant(number, *constant.groups()))
                name = constants[-1].name
            else:
                found = _FIELD.match(_without_comment(line))
                if found is None:
                    raise self.fail(number, f"expected `TYPE NAME`, `TYPE NAME DEFAULT` or `TYPE NAME=VALUE`, got {line!r}")
                fields.append(self.field(number, *found.groups()))
                name = fields[-1].name
            if name in names:
                raise self.fail(number, f"{name!r} is declared twice")
            names.add(name)
        while comment and not comment[-1]:
            comment.pop()
        return MessageSpec("\n".join(comment), tuple(constants), tuple(fields))

    # -- constants and fields -------------------------------------------------------------------

    def constant(self, line: int, type_text: str, name: str, value_text: str) -> ConstantSpec:
        if type_text not in PRIMITIVES:
            raise self.fail(line, f"constant {name} must have a primitive type (bool, int32, string...), not {type_text!r}")
        if type_text in _STRINGS:
            value: Any = self.string_constant(line, value_text)
        else:
            text = _without_comment(value_text).strip()
            if not text:
                raise self.fail(line, f"constant {name} has no value")
            value = self.scalar(line, type_text, text, what=f"constant {name}")
        return ConstantSpec(name, type_text, value, line)

    def string_constant(self, line: int, text: str) -> str:
        text = text.strip()
        if text[:1] in ("'", '"'):  # ROS 2: a quoted string, maybe a comment after it
            value, rest = self.quoted(line, text)
            if rest.strip() and not rest.strip().startswith("#"):
                raise self.fail(line, f"unexpected {rest.strip()!r} after the string")
            return value
        return text  # ROS 1: everything after `=`, as written (a `#` included)

    def field(self, line: int, type_text: str, name: str, default_text: str | None) -> FieldSpec:
        field_type = self.field_type(line, type_text)
        default = None
        if default_text is not None and default_text.strip():
            if not field_type.primitive:
                raise self.fail(line, f"field {name}: only primitive fields and arrays of them take a default")
            default = self.default(line, field_type, default_text.strip(), name)
        return FieldSpec(name, field_type, default, line)

    def field_type(self, line: int, text: str) -> FieldType:
        found = _TYPE.match(text)
        if found is None:
            raise self.fail(line, f"{text!r} is not a type: e.g. int32, string<=10, float64[3], geometry_msgs/Point[]")
        base, bound, bounded, size = found.group("base", "string_bound", "bounded", "size")
        base = self.base_type(line, base)
        if bound is not None and base not in _STRINGS:
            raise self.fail(line, f"only string and wstring take a bound (<=N), not {base}")
        if bounded and not size:
            raise self.fail(line, f"{text!r}: a bounded array needs its bound, e.g. [<=5]")
        array = found.group(0).endswith("]")
        count = int(size) if size else None
        if count is not None and not bounded and count > _MAX_FIXED_SIZE:
            raise self.fail(line, f"{text!r}: a fixed array of more than {_MAX_FIXED_SIZE} items; use [] or [<=N]")
        return FieldType(base, int(bound) if bound is not None else None, array, count, bool(bounded))

    def base_type(self, line: int, text: str) -> str:
        """A primitive, or the full name of a message type (``geometry_msgs/msg/Point``)."""
        if text in PRIMITIVES:
            return text
        if text in _ROS1_ALIASES:
            return _ROS1_ALIASES[text]
        pieces = text.split("/")
        if len(pieces) == 2:
            return f"{pieces[0]}/msg/{pieces[1]}"
        if len(pieces) == 3:
            if pieces[1] not in KINDS:
                raise self.fail(line, f"{text!r} is not a type: package/Name or package/msg/Name")
            return text
        if not text[:1].isupper():  # message names are CamelCase: this was meant as a primitive
            near = difflib.get_close_matches(text, [*PRIMITIVES, *_ROS1_ALIASES], n=1)
            hint = f"did you mean {near[0]}? " if near else ""
            raise self.fail(
                line,
                f"unknown type {text!r} ({hint}a primitive: {', '.join(PRIMITIVES)}; or a message "
                "such as geometry_msgs/Point, or a CamelCase name of this package)",
            )
        return f"{self.package}/msg/{text}"

    # -- values -----------------------------------------------------------------------------------

    def default(self, line: int, field_type: FieldType, text: str, name: str) -> Any:
        what = f"field {name}"
        if not field_type.array:
            return self.bounded_scalar(line, field_type, self.value(line, field_type.base, text, what), what)
        if not text.startswith("["):
            raise self.fail(line, f"{what}: an array's default is a list, e.g. [1, 2, 3]; got {text!r}")
        items = [
            self.bounded_scalar(line, field_type, self.value(line, field_type.base, item, what), what)
            for item in self.list_items(line, text, what)
        ]
        if field_type.size is not None:
            if field_type.bounded and len(items) > field_type.size:
                raise self.fail(line, f"{what}: {len(items)} values for at most {field_type.size}")
            if not field_type.bounded and len(items) != field_type.size:
                raise self.fail(line, f"{what}: {len(items)} values for a fixed array of {field_type.size}")
        return tuple(items)

    def bounded_scalar(self, line: int, field_type: FieldType, value: Any, what: str) -> Any:
        if field_type.string_bound is not None and len(value) > field_type.string_bound:
            raise self.fail(line, f"{what}: {value!r} is longer than {field_type.string_bound} characters")
        return value

    def value(self, line: int, type_name: str, text: str, what: str) -> Any:
        """One value of a field's default (strings quoted or bare; a trailing comment dropped)."""
        if type_name in _STRINGS:
            if text[:1] in ("'", '"'):
                value, rest = self.quoted(line, text)
                if rest.strip() and not rest.strip().startswith("#"):
                    raise self.fail(line, f"{what}: unexpected {rest.strip()!r} after the string")
                return value
            return _without_comment(text).strip()
        return self.scalar(line, type_name, _without_comment(text).strip(), what=what)

    def scalar(self, line: int, type_name: str, text: str, *, what: str) -> Any:
        if type_name == "bool":
            lowered = text.lower()
            if lowered in ("true", "1"):
                return True
            if lowered in ("false", "0"):
                return False
            raise self.fail(line, f"{what}: {text!r} is not a bool (true or false)")
        if type_name in _INTEGERS:
            try:
                number = int(text, 0) if text.lower().startswith(("0x", "-0x", "0b", "0o")) else int(text)
            except ValueError:
                raise self.fail(line, f"{what}: {text!r} is not an integer") from None
            least, most = _INTEGERS[type_name]
            if not least <= number <= most:
                raise self.fail(line, f"{what}: {number} is out of range for {type_name} ({least} to {most})")
            return number
        try:
            real = float(text)
        except ValueError:
            raise self.fail(line, f"{what}: {text!r} is not a number") from None
        if not math.isfinite(real):
            raise self.fail(line, f"{what}: {text!r} is not finite (JSON cannot carry it)")
        return real

    def quoted(self, line: int, text: str) -> tuple[str, str]:
        """The string a quoted literal at the start of ``text`` holds, and the text after it."""
        quote = text[0]
        chars: list[str] = []
        index = 1
        while index < len(text):
            char = text[index]
            if char == "\\" and index + 1 < len(text):
                chars.append(text[index + 1])
                index += 2
                continue
            if char == quote:
                return "".join(chars), text[index + 1 :]
            chars.append(char)
            index += 1
        raise self.fail(line, f"unterminated string {text!r}")

    def list_items(self, line: int, text: str, what: str) -> list[str]:
        """The items of ``[a, "b", 3]`` as texts (quoted items keep their quotes)."""
        items: list[str] = []
        current: list[str] = []
        index = 1
        while index < len(text):
            char = text[index]
            if char in ("'", '"'):
                _, rest = self.quoted(line, text[index:])
                consumed = len(text) - index - len(rest)
                current.append(text[index : index + consumed])
                index += consumed
                continue
            if char in ",]":
                item = "".join(current).strip()
                if item:
                    items.append(item)
                elif char == "," or items:
                    raise self.fail(line, f"{what}: an empty item in {text!r}")
                current = []
                if char == "]":
                    tail = text[index + 1 :].strip()
                    if tail and not tail.startswith("#"):
                        raise self.fail(line, f"{what}: unexpected {tail!r} after the list")
                    return items
            else:
                current.append(char)
            index += 1
        raise self.fail(line, f"{what}: the list {text!r} has no closing ]")


def _without_comment(text: str) -> str:
    """``text`` up to a ``#`` that is not inside quotes."""
    quote = ""
    for index, char in enumerate(text):
        if quote:
            if char == quote:
                quote = ""
        elif char in ("'", '"'):
            quote = char
        elif char == "#":
            return text[:index]
    return text
