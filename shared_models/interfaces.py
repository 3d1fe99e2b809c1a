"""Looking up message and service types by ROS name, and printing them as ``ros2 interface show``.

The text is derived from the models themselves: each field's ROS type comes from the
:class:`~shared_models._message.RosPrimitive` in its ``Annotated`` metadata, or from the nested
message's ``__ros_type__``; constants from the ``ClassVar`` annotations named in
``__ros_constants__``.
"""

from __future__ import annotations

import difflib
import typing
from typing import Annotated, Any, ClassVar, get_args, get_origin

from shared_models._message import (
    ActionType,
    Declared,
    Message,
    RosPrimitive,
    ServiceType,
    registered,
)
from shared_models.catalogue import load_catalogue
from shared_models.close_codes import Close
from shared_models.definitions.index import index
from shared_models.definitions.loader import load_any_package, load_package
from shared_models.errors import SkydeckError

__all__ = [
    "UnknownInterfaceError",
    "all_interfaces",
    "field_types",
    "get_interface",
    "interface_names",
    "interface_text",
]

Interface = type[Message] | type[ServiceType] | type[ActionType]
_KINDS = ("msg", "srv", "action")


class UnknownInterfaceError(SkydeckError, LookupError):
    """Raised by :func:`get_interface` for a name no registered type has; carries ``suggestions``."""

    http_status = 404
    close_code = Close.POLICY

    def __init__(self, name: str, suggestions: list[str]) -> None:
        hint = f" (did you mean {', '.join(suggestions)}?)" if suggestions else ""
        super().__init__(
            f"unknown interface {name!r}{hint}: run `skydeck interface list` to see the known types"
        )
        self.name = name
        self.suggestions = suggestions


def all_interfaces() -> dict[str, Interface]:
    """Every message, service and action type by its full ROS name: the whole catalogue is
    loaded (Skydeck's Python modules and its shipped definition packages; a workspace's packages
    only once used)."""
    load_catalogue()
    for package in index.interface_packages(shipped=True):
        load_package(package.name)
    return registered()


def _is_part(ros_type: str) -> bool:
    """Whether ``ros_type`` is part of a service or an action (``Trigger_Request``,
    ``Fibonacci_Goal``, ``Fibonacci_SendGoal``): ROS's type names have no ``_`` of their own."""
    kind, _, name = ros_type.partition("/")[2].partition("/")
    return ros_type.endswith(("_Request", "_Response")) or (kind == "action" and "_" in name)


def get_interface(name: str) -> Interface:
    """The message or service class named ``name``.

    Accepts ``"geometry_msgs/msg/PoseStamped"``, ROS 1's ``"geometry_msgs/PoseStamped"``,
    ``"std_srvs/srv/Trigger"`` and ``"example_interfaces/action/Fibonacci"``. A package of
    definition files (shipped, or in a workspace this process knows) is loaded on first use.

    Example::

        get_interface("geometry_msgs/msg/Point")(x=1.0)
    """
    name = name.strip()
    parts = name.split("/")
    candidates = [name]
    if len(parts) == 2:
        candidates = [f"{parts[0]}/{kind}/{parts[1]}" for kind in _KINDS]
    if len(parts) in (2, 3):  # only the package named: a process need not load every type
        load_any_package(parts[0])
        found = _first(candidates, registered(parts[0] + "/"))
        if found is not None:
            return found
    known = all_interfaces()
    found = _first(candidates, known)
    if found is not None:
        return found
    raise UnknownInterfaceError(name, _suggestions(name, known))


def _first(candidates: list[str], known: dict[str, Interface]) -> Interface | None:
    return next((known[candidate] for candidate in candidates if candidate in known), None)


def _suggestions(name: str, known: dict[str, Interface]) -> list[str]:
    public = [ros_type for ros_type in known if not _is_part(ros_type)]
    by_short = {_short(ros_type.lower()): ros_type for ros_type in public}
    wanted = _short(name.lower())
    matches = [by_short[m] for m in difflib.get_close_matches(wanted, by_short, n=3, cutoff=0.75)]
    # A bare type name ("PoseStamped") matches on the part after the package.
    last = wanted.rsplit("/", 1)[-1]
    matches += [
        ros_type for short, ros_type in by_short.items() if short.rsplit("/", 1)[-1] == last
    ]
    return list(dict.fromkeys(matches))[:3]


def _short(ros_type: str) -> str:
    return ros_type.replace("/msg/", "/").replace("/srv/", "/").replace("/action/", "/")


def interface_names(kind: str | None = None, *, package: str | None = None) -> list[str]:
    """The sorted names of every registered type; ``kind`` ``"msg"``, ``"srv"`` or ``"action"``
    keeps one kind, ``package`` one package (and loads only that one: shell completion).

    The parts of services and actions (``std_srvs/srv/Trigger_Request``) are left out.
    """
    if kind not in (None, *_KINDS):
        raise ValueError(f"kind must be 'msg', 'srv', 'action' or None, not {kind!r}")
    if package is not None:
        load_any_package(package)
    known = registered(f"{package}/") if package is not None else all_interfaces()
    return sorted(
        ros_type
        for ros_type in known
        if not _is_part(ros_type) and (kind is None or ros_type.split("/")[1] == kind)
    )


def interface_text(name_or_cls: str | Interface) -> str:
    """The ``ros2 interface show`` text of a type: comment, constants, fields with nested types
    indented by a tab per level; for a service the request, ``---`` and the response; for an
    action the goal, result and feedback.
    """
    cls = get_interface(name_or_cls) if isinstance(name_or_cls, str) else name_or_cls
    if isinstance(cls, type) and issubclass(cls, ActionType):
        lines = _message_lines(cls.Goal, comment=True)
        for part in (cls.Result, cls.Feedback):
            lines += ["---", *_message_lines(part, comment=True)]
        return "\n".join(lines)
    if isinstance(cls, type) and issubclass(cls, ServiceType):
        lines = _comment_lines(cls.__ros_comment__)
        lines += _message_lines(cls.Request, comment=True)
        lines.append("---")
        lines += _message_lines(cls.Response, comment=True)
        return "\n".join(lines)
    if isinstance(cls, type) and issubclass(cls, Message):
        return "\n".join(_message_lines(cls, comment=True))
    raise TypeError(f"interface_text needs a message, service or action type, got {cls!r}")


def field_types(cls: type[Message]) -> list[tuple[str, str, type[Message] | None]]:
    """Each field of ``cls`` as ``(name, ROS type text, nested message type or None)``, the
    type text as ``interface show`` prints it (``float64``, ``Point``, ``builtin_interfaces/Time``,
    ``float64[36]``, ``geometry_msgs/Pose[]``)."""
    package = _package(cls.__ros_type__)
    return [
        (name, *_field_type(cls, name, field.annotation, field.metadata, package))
        for name, field in cls.model_fields.items()
    ]


def _comment_lines(comment: str) -> list[str]:
    # The blank line that follows a .msg file's header comment, as `ros2 interface show` prints it.
    return [*comment.splitlines(), ""] if comment else []


def _message_lines(cls: type[Message], *, comment: bool, depth: int = 0) -> list[str]:
    """The lines of ``cls``; nested types are expanded without their comments, as ROS does."""
    indent = "\t" * depth
    lines = _comment_lines(cls.__ros_comment__) if comment else []
    constants = _constant_lines(cls)
    lines += [indent + line for line in constants]
    if constants and comment and cls.model_fields:
        lines.append("")
    package = _package(cls.__ros_type__)
    for field_name, field in cls.model_fields.items():
        ros_type, nested = _field_type(cls, field_name, field.annotation, field.metadata, package)
        declared = any(isinstance(m, Declared) for m in field.metadata)
        value = field.get_default(call_default_factory=True) if declared else field.default
        default = _default_text(value, declared=declared)
        lines.append(f"{indent}{ros_type} {field_name}{default}")
        if nested is not None:
            lines += _message_lines(nested, comment=False, depth=depth + 1)
    return lines


def _constant_lines(cls: type[Message]) -> list[str]:
    if not cls.__ros_constants__:
        return []
    hints = typing.get_type_hints(cls, include_extras=True)
    lines = []
    for constant in cls.__ros_constants__:
        hint = hints.get(constant)
        primitive = _primitive(get_args(hint)[0]) if get_origin(hint) is ClassVar else None
        if primitive is None:
            raise TypeError(
                f"{cls.__ros_type__} constant {constant} needs a ROS-typed ClassVar, e.g. `{constant}: ClassVar[UInt8] = 1`"
            )
        lines.append(f"{primitive.name} {constant}={_value_text(getattr(cls, constant))}")
    return lines


def _primitive(annotation: Any) -> RosPrimitive | None:
    if get_origin(annotation) is Annotated:
        return next((m for m in annotation.__metadata__ if isinstance(m, RosPrimitive)), None)
    return None


def _field_type(
    owner: type[Message], field_name: str, annotation: Any, metadata: list[Any], package: str
) -> tuple[str, type[Message] | None]:
    """The ROS type text of a field, and the message type to expand below it (if any)."""
    primitive = next((m for m in metadata if isinstance(m, RosPrimitive)), None)
    if primitive is not None:
        return primitive.name, None
    if isinstance(annotation, type) and issubclass(annotation, Message):
        return _type_ref(annotation, package), annotation
    if get_origin(annotation) is list:
        (item,) = get_args(annotation)
        brackets = _array_brackets(metadata)
        item_primitive = _primitive(item)
        if item_primitive is not None:
            return item_primitive.name + brackets, None
        if isinstance(item, type) and issubclass(item, Message):
            return _type_ref(item, package) + brackets, item
    raise TypeError(
        f"{owner.__ros_type__} field {field_name} has no ROS type: annotate it with a shared_models "
        f"alias (Float64, UInt32...), a Message or a list of either"
    )


def _array_brackets(metadata: list[Any]) -> str:
    """``[36]`` for a fixed size, ``[<=1]`` for a bounded one, ``[]`` for any length."""
    # Pydantic keeps Field(min_length=, max_length=) as annotated_types' MinLen and MaxLen.
    least = next((m.min_length for m in metadata if hasattr(m, "min_length")), 0)
    most = next((m.max_length for m in metadata if hasattr(m, "max_length")), None)
    if most is None:
        return "[]"
    return f"[{most}]" if least == most else f"[<={most}]"


def _package(ros_type: str) -> str:
    return ros_type.split("/", 1)[0]


def _type_ref(cls: type[Message], package: str) -> str:
    """``Point`` within the same package, ``builtin_interfaces/Time`` across packages."""
    type_package, _, short = cls.__ros_type__.partition("/")
    short = short.rsplit("/", 1)[-1]
    return short if type_package == package else f"{type_package}/{short}"


def _default_text(default: Any, *, declared: bool = False) -> str:
    # ROS prints the defaults a .msg file declares: ours are those that are not the type's zero,
    # and the zeros a field marks as Declared.
    if isinstance(default, bool | int | float) and (default != 0 or declared):
        return " " + _value_text(default)
    if isinstance(default, str) and (default or declared):
        return f' "{default}"'
    if isinstance(default, list) and declared:  # an array's declared default (`int32[] a [1, 2]`)
        items = (f'"{item}"' if isinstance(item, str) else _value_text(item) for item in default)
        return f" [{', '.join(items)}]"
    return ""


def _value_text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
