"""Loading definition files into the one type system, and what a process tells another about them.

- :func:`load_package` loads every ``msg``/``srv``/``action`` file of a package the index knows
  (a shipped one, or a workspace's), building each type after the types it uses: its own
  package's, Skydeck's Python-declared packages (``geometry_msgs``...), or other packages the
  index knows. The first use of a package loads it (``from my_pkg.msg import Status``,
  ``get_interface("my_pkg/msg/Status")``).
- :func:`definitions_of` is the text of the non-shipped files a type needs (itself and the types
  it nests), keyed by the type each declares: what a node sends the core when it registers, and
  what the core's ``/api/interfaces/NAME`` hands to the CLI.
- :func:`learn_definitions` builds types from such texts (the core, the CLI). A type already
  known with other fields is a :class:`~shared_models.definitions.errors.DefinitionConflict`:
  one process cannot hold two versions of a type (ROS 1 refuses the connection on its md5 too).
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable, Mapping
from functools import cache
from pathlib import Path
from typing import Any, get_args, get_origin

from shared_models._message import ActionType, Message, ServiceType, forget_interfaces, registered
from shared_models.catalogue import MESSAGE_PACKAGES
from shared_models.definitions.actions import action_classes
from shared_models.definitions.builder import Resolver, message_class, service_class
from shared_models.definitions.errors import DefinitionConflict, DefinitionError
from shared_models.definitions.index import index
from shared_models.definitions.parser import Definition, FieldSpec, parse_definition

__all__ = ["definition_of", "definitions_of", "is_loaded", "learn_definitions", "load_any_package", "load_package", "unit_of"]

# Every definition a class of this process was built from, by the type its file declares.
_DEFINITIONS: dict[str, Definition] = {}
_LOADED: set[str] = set()  # packages whose files are all built (or being built)
# Suffixes of the types an action derives (ROS 2's, then ROS 1's actionlib messages).
_ACTION_PARTS = ("_Goal", "_Result", "_Feedback", "_SendGoal_Request", "_SendGoal_Response", "_SendGoal",
                 "_GetResult_Request", "_GetResult_Response", "_GetResult", "_FeedbackMessage")  # fmt: skip
_ACTIONLIB_PARTS = ("ActionGoal", "ActionResult", "ActionFeedback", "Action", "Goal", "Result", "Feedback")


def load_package(name: str) -> bool:
    """Build every type of the package ``name`` (once); False when no known package has files."""
    if name in _LOADED:
        return True
    package = index.find(name)
    if package is None or not package.has_interfaces:
        return False
    _LOADED.add(name)
    try:
        sources = {unit: _FileSource(unit, path, package.shipped) for unit, path in package.files.items()}
        _Build(sources).all()
    except BaseException:
        _LOADED.discard(name)  # a later use says the same thing again
        raise
    return True


def is_loaded(package: str) -> bool:
    """Whether the files of ``package`` are loaded (or being loaded)."""
    return package in _LOADED


def learn_definitions(texts: Mapping[str, str], *, source: str = "") -> list[str]:
    """Build the types of ``texts`` (file text by the type it declares) not known yet; returns
    the names built. DefinitionError for a text that cannot be read, DefinitionConflict for a
    type known with other fields or constants (``source`` says who sent them, for the message)."""
    suffix = f" (from {source})" if source else ""
    parsed = {unit: parse_definition(text, unit, origin=f"{unit}{suffix}") for unit, text in texts.items()}
    new = {}
    for unit, definition in parsed.items():
        known = _DEFINITIONS.get(unit)
        if known is None and unit in registered(unit):
            raise DefinitionConflict(f"{unit}{suffix} is a type Skydeck declares itself: rename the package")
        if known is None:
            new[unit] = _TextSource(definition)
        elif known.signature() != definition.signature():
            raise DefinitionConflict(
                f"{unit}{suffix} differs from the definition this process already has (from {known.origin}): "
                "a type cannot change while the core runs; restart the core (`skydeck core`) to use the new one"
            )
    _Build(new).all()
    return sorted(new)


def definition_of(cls: type) -> Definition | None:
    """The definition ``cls`` was built from (None for a type declared in Python)."""
    unit = cls.__dict__.get("__ros_definition__")
    return _DEFINITIONS.get(unit) if unit else None


def definitions_of(classes: Iterable[type]) -> dict[str, str]:
    """The texts of the definitions ``classes`` need that Skydeck does not ship, by type name."""
    found: dict[str, str] = {}
    for cls in classes:
        found.update(_needed(cls))
    return found


def unit_of(ros_type: str) -> str:
    """The type whose file declares ``ros_type`` (``pkg/srv/X_Request`` -> ``pkg/srv/X``)."""
    package, kind, name = ros_type.split("/")
    if kind == "srv":
        return f"{package}/srv/{name.removesuffix('_Request').removesuffix('_Response')}"
    if kind == "action":
        for suffix in _ACTION_PARTS:
            if name.endswith(suffix):
                return f"{package}/action/{name.removesuffix(suffix)}"
    return ros_type


@cache
def _needed(cls: type) -> dict[str, str]:
    found: dict[str, str] = {}
    definition = definition_of(cls)
    if definition is not None and not _shipped(definition):
        found[definition.ros_type] = definition.text
    for nested in _nested(cls):
        found.update(_needed(nested))
    return found


def _nested(cls: type) -> list[type]:
    if isinstance(cls, type) and issubclass(cls, ActionType):
        return [cls.Goal, cls.Result, cls.Feedback]
    if isinstance(cls, type) and issubclass(cls, ServiceType):
        return [cls.Request, cls.Response]
    if not (isinstance(cls, type) and issubclass(cls, Message)):
        return []
    nested = []
    for field in cls.model_fields.values():
        annotation: Any = field.annotation
        if get_origin(annotation) is list:
            annotation = get_args(annotation)[0]
        if isinstance(annotation, type) and issubclass(annotation, Message):
            nested.append(annotation)
    return nested


def _shipped(definition: Definition) -> bool:
    package = index.find(definition.package)
    return package is not None and package.shipped and definition.ros_type in package.files


class _FileSource:
    """A definition still in its file; parsed when first needed."""

    def __init__(self, unit: str, path: Path, shipped: bool) -> None:
        self.unit = unit
        self.path = path
        self.shipped = shipped

    def definition(self) -> Definition:
        package, kind, name = self.unit.split("/")
        origin = f"{package}/{kind}/{name}.{kind}"
        try:
            text = self.path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            raise DefinitionError(origin, None, f"cannot read {self.path}: {error}") from None
        return parse_definition(text, self.unit, origin=origin)


class _TextSource:
    """A definition already parsed (from a text another process sent)."""

    def __init__(self, definition: Definition) -> None:
        self._definition = definition

    def definition(self) -> Definition:
        return self._definition


class _Build:
    """Builds a set of definitions, each after the types it uses."""

    def __init__(self, sources: Mapping[str, _FileSource | _TextSource]) -> None:
        self.sources = sources
        self.building: list[str] = []

    def all(self) -> None:
        for unit in self.sources:
            self.unit(unit)

    def unit(self, unit: str) -> None:
        if unit in _DEFINITIONS:
            return
        definition = self.sources[unit].definition()
        if unit in self.building:
            chain = " -> ".join([*self.building[self.building.index(unit) :], unit])
            raise DefinitionError(definition.origin, None, f"{unit} contains itself ({chain}): a message cannot nest itself")
        self.building.append(unit)
        try:
            for field in definition.dependencies():
                self.resolve(field.type.base, field, definition)
            before = set(registered())
            try:
                build_definition(definition, lambda name, field: self.resolve(name, field, definition))
            except BaseException as error:
                # None of a half-built definition stays: the fixed file builds again
                forget_interfaces(set(registered()) - before - _built_elsewhere(before))
                if isinstance(error, TypeError):  # a name registered twice (an action's ROS 1 names and a .msg)
                    raise DefinitionError(definition.origin, None, str(error)) from None
                raise
            _DEFINITIONS[unit] = definition
        finally:
            self.building.pop()

    def resolve(self, type_name: str, field: FieldSpec, definition: Definition) -> type:
        """The class of ``type_name``, building or loading what declares it first."""
        known = registered(type_name).get(type_name)
        if known is not None:
            return known
        unit = self._unit_here(type_name)
        if unit is not None:
            self.unit(unit)
        else:
            load_any_package(type_name.split("/", 1)[0])
        known = registered(type_name).get(type_name)
        if known is None:
            raise DefinitionError(definition.origin, field.line, _unknown(type_name, definition))
        return known

    def _unit_here(self, type_name: str) -> str | None:
        """The definition among ours that declares ``type_name`` (an action's ROS 1 names too)."""
        unit = unit_of(type_name)
        if unit in self.sources:
            return unit
        package, kind, name = type_name.split("/")
        if kind == "msg":
            for suffix in _ACTIONLIB_PARTS:
                action = f"{package}/action/{name.removesuffix(suffix)}"
                if name.endswith(suffix) and action in self.sources:
                    return action
        return None


def build_definition(definition: Definition, resolve: Resolver) -> list[type]:
    """Every class ``definition`` declares (a message; a service and its two parts; an action
    and everything derived from it), registered under their ROS names."""
    if definition.kind == "msg":
        return [message_class(definition.ros_type, definition.parts[0], resolve, definition=definition)]
    if definition.kind == "srv":
        request, response = definition.parts
        return list(service_class(definition.ros_type, request, response, resolve, definition=definition))
    return action_classes(definition, resolve)


def _built_elsewhere(before: set[str]) -> set[str]:
    """Types registered since ``before`` that belong to definitions built meanwhile (a dependency
    loaded on the way), which stay."""
    kept = set()
    for name, cls in registered().items():
        unit = cls.__dict__.get("__ros_definition__")
        if name not in before and (unit is None or unit in _DEFINITIONS):
            kept.add(name)
    return kept


def load_any_package(package: str) -> None:
    """Make the types of ``package`` known: import its Python module (``geometry_msgs``) or load
    its definition files; nothing if Skydeck knows no such package."""
    if package in MESSAGE_PACKAGES:
        importlib.import_module(f"shared_models.{package}")
    else:
        load_package(package)


def _unknown(type_name: str, definition: Definition) -> str:
    package, kind, name = type_name.split("/")
    shown = name if package == definition.package else f"{package}/{name}"
    have = sorted(n.rsplit("/", 1)[-1] for n in registered(f"{package}/{kind}/") if "_" not in n.rsplit("/", 1)[-1])
    if have:
        return f"unknown type {shown!r}: {package} has no {kind} {name} (it has: {', '.join(have)})"
    if package == definition.package:
        return f"unknown type {shown!r}: there is no {package}/{kind}/{name}.{kind}"
    return f"unknown type {shown!r}: no package {package} is known (is it in the workspace? `--workspace DIR`)"
