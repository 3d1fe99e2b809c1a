"""ROS 2 message definitions: what a Skydeck type is in ROS 2's ``.msg`` language, and back.

A definition is a :class:`MessageSpec`: the type's name and its fields in order, each a
:class:`FieldSpec` (a primitive or a nested message, maybe an array). Specs come from three
places, and the CDR codec (:mod:`shared_models.cdr`) works from any of them:

- a Skydeck model (:func:`message_spec`): its ROS 2 view, without the fields ROS 2's type does
  not have (``Header.seq``, kept from ROS 1, marked :class:`~shared_models._message.Ros1Only`);
- the text of a ``.msg`` file or of an MCAP ``ros2msg`` schema (:func:`parse_definition`): the
  type's own definition, then each type it uses after a line of ``=`` and ``MSG: pkg/Name``
  (read into specs for the codec, never into classes: :mod:`shared_models.definitions` makes
  Skydeck's types from definition files; this reads a recording's, whatever Skydeck holds);
- a definition written out by :func:`definition_text` (what ``skydeck bag record --encoding cdr``
  puts in its schemas) or :func:`msg_file_text` (the ``.msg`` file the ROS 2 interface build
  compiles).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from shared_models._message import Message, Ros1Only, ServiceType
from shared_models.definitions.errors import DefinitionError
from shared_models.interfaces import field_types

__all__ = [
    "PRIMITIVES",
    "FieldSpec",
    "MessageSpec",
    "definition_text",
    "message_spec",
    "msg_file_text",
    "parse_definition",
    "ros2_type_name",
    "skydeck_type_name",
    "specs_of",
    "srv_file_text",
]

# Every primitive of the .msg language, with the Python kind its value takes.
PRIMITIVES = {
    "bool": bool, "byte": int, "char": int, "int8": int, "uint8": int, "int16": int, "uint16": int,
    "int32": int, "uint32": int, "int64": int, "uint64": int, "float32": float, "float64": float,
    "string": str, "wstring": str,
}
# ROS 1 spellings a .msg file may still use.
_ALIASES = {"time": "builtin_interfaces/msg/Time", "duration": "builtin_interfaces/msg/Duration"}
_SEPARATOR = "=" * 80


@dataclass(frozen=True)
class FieldSpec:
    """One field: ``type`` is a primitive (``float64``) or a message (``geometry_msgs/msg/Point``);
    ``array`` is None (one value), ``-1`` (any length), or the length (``bounded``: at most)."""

    name: str
    type: str
    array: int | None = None
    bounded: bool = False
    default: str = ""  # as the .msg text writes it, if it declares one

    @property
    def is_primitive(self) -> bool:
        return self.type in PRIMITIVES

    def type_text(self, package: str) -> str:
        """The field's type as a ``.msg`` file spells it (``Point``, ``builtin_interfaces/Time``,
        ``float64[36]``, ``FloatingPointRange[<=1]``)."""
        text = self.type if self.is_primitive else _reference(self.type, package)
        if self.array is None:
            return text
        if self.array < 0:
            return text + "[]"
        return f"{text}[<={self.array}]" if self.bounded else f"{text}[{self.array}]"


@dataclass(frozen=True)
class MessageSpec:
    """A message type's name (``pkg/msg/Name``), fields in order and constants."""

    name: str
    fields: tuple[FieldSpec, ...]
    # (type, name, value as written)
    constants: tuple[tuple[str, str, str], ...] = ()

    @property
    def package(self) -> str:
        return self.name.split("/", 1)[0]


# -- from Skydeck's models ----------------------------------------------------------------------

_FIELD_TYPE = re.compile(r"^(?P<base>[^\[]+)(?:\[(?P<bound><=)?(?P<size>\d*)\])?$")


def message_spec(cls: type[Message]) -> MessageSpec:
    """The ROS 2 definition of a Skydeck message type (its fields ROS 2 has, in order)."""
    package = cls.__ros_type__.split("/", 1)[0]
    fields = []
    for name, text, nested in field_types(cls):
        if any(isinstance(m, Ros1Only) for m in cls.model_fields[name].metadata):
            continue
        match = _FIELD_TYPE.match(text)
        if match is None:  # field_types only writes what the pattern reads
            raise DefinitionError(cls.__ros_type__, None, f"{name}: unreadable type {text!r}")
        base = nested.__ros_type__ if nested is not None else _full_type(match["base"], package)
        array = None if match["size"] is None else int(match["size"]) if match["size"] else -1
        # byte[]/uint8[] are one primitive alias in Skydeck ("uint8[]"): the same here
        fields.append(FieldSpec(name, base, array, bool(match["bound"]), _default(cls, name)))
    constants = tuple(_constants(cls))
    return MessageSpec(cls.__ros_type__, tuple(fields), constants)


def _default(cls: type[Message], name: str) -> str:
    # Only the defaults a .msg file would declare (what `interface show` prints), never a zero.
    from shared_models.interfaces import _default_text

    return _default_text(cls.model_fields[name].default).strip()


def _constants(cls: type[Message]) -> Iterator[tuple[str, str, str]]:
    from shared_models.interfaces import _constant_lines

    for line in _constant_lines(cls):
        declaration, _, value = line.partition("=")
        kind, _, name = declaration.partition(" ")
        yield kind, name, value


def specs_of(cls: type[Message]) -> dict[str, MessageSpec]:
    """The spec of ``cls`` and of every message type inside it, by name, ``cls`` first."""
    specs: dict[str, MessageSpec] = {}

    def add(model: type[Message]) -> None:
        if model.__ros_type__ in specs:
            return
        spec = specs[model.__ros_type__] = message_spec(model)
        nested = {n: t for n, _, t in field_types(model) if t is not None}
        for item in spec.fields:
            if not item.is_primitive:
                add(nested[item.name])

    add(cls)
    return specs


# -- writing definitions ----------------------------------------------------------------------


def _reference(type_name: str, package: str) -> str:
    """How a definition names a message type: ``Point`` within its package, ``pkg/Name`` across
    packages, and ``pkg/action/Name`` for an action's parts (which are no ``msg``)."""
    type_package, kind, short = type_name.split("/")
    if kind != "msg":
        return type_name
    return short if type_package == package else f"{type_package}/{short}"


def _spec_lines(spec: MessageSpec) -> list[str]:
    lines = [f"{kind} {name}={value}" for kind, name, value in spec.constants]
    for item in spec.fields:
        default = f" {item.default}" if item.default else ""
        lines.append(f"{item.type_text(spec.package)} {item.name}{default}")
    return lines


def msg_file_text(cls: type[Message]) -> str:
    """The ``.msg`` file of ``cls`` as ROS 2's interface build reads it."""
    return "\n".join(_spec_lines(message_spec(cls))) + "\n"


def srv_file_text(cls: type[ServiceType]) -> str:
    """The ``.srv`` file of a service: the request, ``---``, the response."""
    request = _spec_lines(message_spec(cls.Request))
    response = _spec_lines(message_spec(cls.Response))
    return "\n".join([*request, "---", *response]) + "\n"


def definition_text(cls: type[Message]) -> str:
    """The MCAP ``ros2msg`` schema of ``cls``: its definition, then each type it uses, after a line
    of ``=`` and ``MSG: pkg/Name`` (the form rosbag2 writes, read by ``rosbags`` and ``mcap_ros2``)."""
    specs = list(specs_of(cls).values())
    parts = ["\n".join(_spec_lines(specs[0]))]
    for spec in specs[1:]:
        parts.append(f"{_SEPARATOR}\nMSG: {_reference(spec.name, '')}\n" + "\n".join(_spec_lines(spec)))
    return "\n".join(parts) + "\n"


# -- reading definitions ----------------------------------------------------------------------

_LINE = re.compile(
    r"^(?P<type>[A-Za-z_][\w/]*(?:<=\d+)?(?:\[(?:<=)?\d*\])?)\s+(?P<name>[A-Za-z_]\w*)\s*(?P<rest>.*)$"
)


def parse_definition(name: str, text: str) -> dict[str, MessageSpec]:
    """Every message spec in a ``.msg`` or ``ros2msg`` text, by full name, ``name``'s first.

    Raises :class:`DefinitionError` naming the line it cannot read, or a type used and not defined
    (the builtin_interfaces ``Time`` and ``Duration`` are known without a definition).
    """
    name = _full_name(name)
    sections: list[tuple[str, list[str]]] = [(name, [])] if not text.startswith("MSG:") else []
    current: list[str] = sections[0][1] if sections else []
    for line in text.splitlines():
        if line.startswith("=") and set(line.strip()) == {"="}:
            continue
        if line.startswith("MSG:"):
            current = []
            sections.append((_full_name(line[4:].strip()), current))
            continue
        current.append(line)
    specs = {}
    for section_name, lines in sections:
        specs[section_name] = _parse_section(section_name, lines)
    _check_resolved(name, specs)
    return specs


def _parse_section(name: str, lines: list[str]) -> MessageSpec:
    package = name.split("/", 1)[0]
    fields, constants = [], []
    for number, raw in enumerate(lines, 1):
        line = raw.split("#", 1)[0].strip() if '"' not in raw and "'" not in raw else _strip_comment(raw)
        if not line:
            continue
        match = _LINE.match(line)
        if match is None:
            constant = re.match(r"^(\w+)\s+(\w+)\s*=\s*(.*)$", line)
            if constant is None:
                raise DefinitionError(name, number, f"cannot read {raw.strip()!r}")
            constants.append((constant[1], constant[2], constant[3].strip()))
            continue
        rest = match["rest"].strip()
        if rest.startswith("="):
            constants.append((match["type"], match["name"], rest[1:].strip()))
            continue
        fields.append(_field(name, package, match["type"], match["name"], rest))
    return MessageSpec(name, tuple(fields), tuple(constants))


def _strip_comment(line: str) -> str:
    # A '#' inside a quoted default is not a comment.
    quote = ""
    for index, char in enumerate(line):
        if char in "\"'" and not quote:
            quote = char
        elif char == quote:
            quote = ""
        elif char == "#" and not quote:
            return line[:index].strip()
    return line.strip()


def _field(owner: str, package: str, text: str, name: str, default: str) -> FieldSpec:
    match = _FIELD_TYPE.match(text)
    if match is None:
        raise DefinitionError(owner, None, f"cannot read the type {text!r} of {name}")
    base = re.sub(r"<=\d+$", "", match["base"])  # string<=10: a bound ROS 2 keeps, CDR does not
    array = None if match["size"] is None else int(match["size"]) if match["size"] else -1
    return FieldSpec(name, _full_type(base, package), array, bool(match["bound"]), default)


def _full_type(base: str, package: str) -> str:
    if base in PRIMITIVES:
        return base
    if base in _ALIASES:
        return _ALIASES[base]
    if base == "Header":  # ROS 1 habit: a bare Header is std_msgs'
        return "std_msgs/msg/Header"
    parts = base.split("/")
    if len(parts) == 1:
        return f"{package}/msg/{base}"
    if len(parts) == 3:  # pkg/action/Name: an action's part, named whole
        return base
    return f"{parts[0]}/msg/{parts[-1]}"


def _full_name(name: str) -> str:
    parts = name.strip().split("/")
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    return name.strip()


def _check_resolved(name: str, specs: dict[str, MessageSpec]) -> None:
    for spec in list(specs.values()):
        for item in spec.fields:
            if item.is_primitive or item.type in specs:
                continue
            builtin = _BUILTINS.get(item.type)
            if builtin is None:
                raise DefinitionError(
                    name, None, f"{spec.name}.{item.name} is of type {item.type}, which the definition does not include"
                )
            specs[item.type] = builtin


_TIME_FIELDS = (FieldSpec("sec", "int32"), FieldSpec("nanosec", "uint32"))
_BUILTINS = {
    "builtin_interfaces/msg/Time": MessageSpec("builtin_interfaces/msg/Time", _TIME_FIELDS),
    "builtin_interfaces/msg/Duration": MessageSpec("builtin_interfaces/msg/Duration", _TIME_FIELDS),
}


# -- the one type whose name differs -----------------------------------------------------------

_TIME = "builtin_interfaces/msg/Time"
_CLOCK = "rosgraph_msgs/msg/Clock"


def ros2_type_name(topic: str, type_name: str) -> str:
    """The ROS 2 type of a Skydeck topic: the same name, but ``/clock``'s, which ROS 2 types
    ``rosgraph_msgs/msg/Clock`` and Skydeck (the seed) ``builtin_interfaces/msg/Time``. A Clock
    is one Time, so the two have the same CDR: only the name changes."""
    return _CLOCK if topic == "/clock" and type_name == _TIME else type_name


def skydeck_type_name(topic: str, type_name: str) -> str:
    """The Skydeck type of a ROS 2 topic (the same name, but ``/clock``'s)."""
    return _TIME if topic == "/clock" and type_name == _CLOCK else type_name
