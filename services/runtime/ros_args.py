"""ROS command-line arguments: ROS 2's ``--ros-args -p NAME:=VALUE --params-file FILE.yaml
-r FROM:=TO`` and ROS 1's bare ``name:=value`` arguments.

    skydeck run ai --landing home --ros-args -p visit_radius:=0.5 --params-file ai.yaml
    skydeck run my_node.py --ros-args -r scan:=/robot1/scan -r __ns:=/robot1 -r __node:=left
    skydeck run talker.py chatter:=/news __name:=talker2 _rate:=5      # ROS 1's spelling

Everything between ``--ros-args`` and ``--`` (or the end) is ROS's; the rest is the program's.
Values are read as YAML, as ROS does: ``-p speed:=0.3`` is a double, ``-p name:=robot1`` a string,
``-p flags:=[1,2]`` an integer array; ``-p NODE:NAME:=VALUE`` sets it for one node only. A params
file is ROS 2's::

    /ai:                      # a node's full name, or /** for every node
      ros__parameters:
        visit_radius: 0.5
        gains: {p: 1.0}       # nested names: gains.p

Remapping (``-r FROM:=TO``, ``-r NODE:FROM:=TO`` for one node) renames a topic or service as the
node resolves it; ``-r __ns:=/robot1`` puts the node in a namespace and ``-r __node:=name``
renames it (rules for one node match its name as the program gave it). The first rule that
matches a name applies, as in ROS 2. ROS 1's arguments (:func:`parse_ros1_args`) are the same
rules: ``from:=to``, ``__ns:=``, ``__name:=``, and ``_param:=value`` for a private parameter.
Where and how the rules apply to names is :class:`NameResolver`. One process has one set (:func:`set_process_ros_arguments`), which every node in it reads, as
ROS's global arguments.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from services.runtime.parameter import Parameter
from shared_models.errors import SkydeckError
from shared_models.names import InvalidNameError, resolve_name, resolve_node_name
from shared_models.text_files import parse_yaml

__all__ = [
    "NameResolver",
    "ParameterRule",
    "RemapRule",
    "RosArguments",
    "RosArgumentsError",
    "parameter_value",
    "parse_ros1_args",
    "parse_ros_args",
    "process_ros_arguments",
    "rules_from_params_yaml",
    "set_process_ros_arguments",
    "split_ros_args",
]

ROS_ARGS = "--ros-args"
_END = "--"
_PARAMETERS_KEY = "ros__parameters"


class RosArgumentsError(SkydeckError):
    """A ``--ros-args`` argument or params file Skydeck cannot read (the message says which)."""

    http_status = 400


@dataclass(frozen=True)
class ParameterRule:
    """Parameter values for the nodes whose full name matches ``node`` (``/**``: every node)."""

    node: str
    values: dict[str, Any]

    def matches(self, node_name: str) -> bool:
        return _node_pattern(self.node).fullmatch(node_name) is not None


@dataclass(frozen=True)
class RemapRule:
    """``source:=target`` for the node named ``node`` (as its program named it), or every node.

    ``source`` is a topic or service name, or ``__ns`` / ``__node`` (the namespace, the name).
    """

    node: str | None
    source: str
    target: str

    def applies_to(self, node_name: str) -> bool:
        return self.node is None or self.node.lstrip("/") == node_name.lstrip("/")


@dataclass
class RosArguments:
    """The ROS arguments of a process (or of one node's ``cli_args``), in the order given."""

    parameter_rules: list[ParameterRule] = field(default_factory=list)
    remap_rules: list[RemapRule] = field(default_factory=list)

    def node_name_for(self, node_name: str) -> str:
        """The name a node called ``node_name`` by its program takes (``__node``/``__name``)."""
        return self._special(node_name, ("__node", "__name")) or node_name

    def namespace_for(self, node_name: str) -> str | None:
        """The namespace ``__ns`` gives the node, if any."""
        return self._special(node_name, ("__ns",))

    def remaps_for(self, node_name: str) -> list[tuple[str, str]]:
        """The (source, target) name rules for the node, first first."""
        return [
            (r.source, r.target)
            for r in self.remap_rules
            if r.applies_to(node_name) and not r.source.startswith("__")
        ]

    def _special(self, node_name: str, sources: tuple[str, ...]) -> str | None:
        found = None
        for rule in self.remap_rules:  # a later __ns/__node wins, as a later -p does
            if rule.source in sources and rule.applies_to(node_name):
                found = rule.target
        return found

    def overrides_for(self, node_name: str) -> dict[str, Any]:
        """The parameter values meant for ``node_name``; a later rule wins over an earlier one."""
        values: dict[str, Any] = {}
        for rule in self.parameter_rules:
            if rule.matches(node_name):
                values.update(rule.values)
        return values

    def __add__(self, other: RosArguments) -> RosArguments:
        return RosArguments(
            self.parameter_rules + other.parameter_rules, self.remap_rules + other.remap_rules
        )


def split_ros_args(argv: list[str]) -> tuple[list[str], list[str]]:
    """(the program's arguments, the ROS arguments without the ``--ros-args``/``--`` markers)."""
    program: list[str] = []
    ros: list[str] = []
    inside = False
    for arg in argv:
        if arg == ROS_ARGS:
            inside = True
        elif inside and arg == _END:
            inside = False
        else:
            (ros if inside else program).append(arg)
    return program, ros


def parse_ros_args(args: list[str]) -> RosArguments:
    """Read ROS arguments (what follows ``--ros-args``); one clear error for anything else."""
    parsed = RosArguments()
    words = iter(args)
    for word in words:
        if word in ("-p", "--param"):
            parsed.parameter_rules.append(_parameter_assignment(_next(words, word, "NAME:=VALUE")))
        elif word == "--params-file":
            parsed.parameter_rules.extend(_params_file(_next(words, word, "FILE.yaml")))
        elif word in ("-r", "--remap"):
            parsed.remap_rules.append(_remap(_next(words, word, "FROM:=TO"), word))
        elif word in ("-e", "--enclave", "--log-level", "--log-config-file"):
            _next(words, word, "a value")
            raise RosArgumentsError(
                f"--ros-args {word} is not supported by Skydeck (it reads -p, --params-file and -r)"
            )
        else:
            raise RosArgumentsError(
                f"unknown ROS argument {word!r}: Skydeck reads -p NAME:=VALUE, --params-file FILE and -r FROM:=TO"
            )
    return parsed


def parse_ros1_args(argv: list[str]) -> tuple[list[str], RosArguments]:
    """(the program's arguments, the ROS 1 arguments among ``argv``): ``from:=to`` remaps,
    ``__ns:=``, ``__name:=``, ``_param:=value`` (a private parameter: one of the node's), as
    ``rospy.myargv`` splits them. ``__master``, ``__ip``, ``__hostname`` and ``__log`` are
    read and ignored (Skydeck finds its core through SKYDECK_CORE_URL)."""
    program: list[str] = []
    parsed = RosArguments()
    for arg in argv:
        source, separator, target = arg.partition(":=")
        if not separator or arg.startswith("-"):
            program.append(arg)
        elif source in ("__master", "__ip", "__hostname", "__log"):
            continue
        elif source in ("__ns", "__name"):
            parsed.remap_rules.append(RemapRule(None, source, target))
        elif source.startswith("_") and not source.startswith("__"):
            try:
                parsed.parameter_rules.append(ParameterRule("/**", {source[1:]: parameter_value(target)}))
            except RosArgumentsError as error:
                raise RosArgumentsError(f"{arg}: {error}") from None
        else:
            parsed.remap_rules.append(_remap(arg, "ROS 1 argument"))
    return program, parsed


def _remap(text: str, flag: str) -> RemapRule:
    """``FROM:=TO``, ``NODE:FROM:=TO``, ``__ns:=/robot1``, ``__node:=name``, checked."""
    source_text, separator, target = text.partition(":=")
    node, _, source = source_text.rpartition(":")
    if not separator or not source or not target:
        raise RosArgumentsError(f"{flag} {text!r}: expected FROM:=TO, e.g. -r scan:=/robot1/scan")
    try:
        if source == "__ns":
            _namespace(target)
        elif source in ("__node", "__name"):
            resolve_node_name(target)
        else:
            for name in (source, target):
                _check_name(name)
    except InvalidNameError as error:
        raise RosArgumentsError(f"{flag} {text}: {error}") from None
    return RemapRule(node or None, source, target)


def _check_name(name: str) -> None:
    resolve_name(name.removeprefix("~").lstrip("/") or name)


def _namespace(text: str) -> str:
    """A namespace as ``__ns`` gives it: absolute, ``/`` alone for none."""
    if text in ("", "/"):
        return "/"
    return resolve_name(text if text.startswith("/") else "/" + text)


class NameResolver:
    """How one node turns the names its program uses into the graph's: expansion in the node's
    namespace (``scan`` -> ``/robot1/scan``), private names (``~/cmd`` or ROS 1's ``~cmd`` ->
    ``/robot1/my_node/cmd``), then the first remap rule whose source expands to the same name.

        resolver = NameResolver("/robot1", "my_node", [("scan", "base_scan")])
        resolver.resolve("scan")     # "/robot1/base_scan"
    """

    def __init__(self, namespace: str, node_name: str, remaps: list[tuple[str, str]]) -> None:
        self.namespace = _namespace(namespace)
        self.node_name = resolve_node_name(node_name).lstrip("/")
        self.full_node_name = self.namespace.rstrip("/") + "/" + self.node_name
        self._remaps = [(self.expand(source), target) for source, target in remaps]

    def expand(self, name: str) -> str:
        """``name`` made absolute in this node's namespace (no remapping)."""
        if name.startswith("~"):
            rest = name[1:].lstrip("/")
            return resolve_name(rest, self.full_node_name) if rest else self.full_node_name
        return resolve_name(name, self.namespace)

    def resolve(self, name: str) -> str:
        """The graph's name for ``name``: expanded, then remapped."""
        expanded = self.expand(name)
        for source, target in self._remaps:
            if source == expanded:
                return self.expand(target)
        return expanded


def _next(words: Any, flag: str, what: str) -> str:
    try:
        return str(next(words))
    except StopIteration:
        raise RosArgumentsError(f"--ros-args {flag} needs {what}") from None


def _parameter_assignment(text: str) -> ParameterRule:
    target, separator, value_text = text.partition(":=")
    if not separator or not target:
        raise RosArgumentsError(f"-p {text!r}: expected NAME:=VALUE, e.g. -p speed:=0.3")
    node, _, name = target.rpartition(":")
    try:
        value = parameter_value(value_text)
    except RosArgumentsError as error:
        raise RosArgumentsError(f"-p {text}: {error}") from None
    return ParameterRule(node or "/**", {name: value})


def parameter_value(text: str) -> Any:
    """A parameter value as typed on a command line, read as YAML (``0.3``, ``true``, ``[1, 2]``).

    A scalar YAML reads as something else than a parameter value (``null``, a date) stays the
    text as typed, a string; an empty text is the empty string.
    """
    try:
        value = yaml.safe_load(text) if text.strip() else ""
    except yaml.YAMLError:
        value = text
    try:
        Parameter.Type.from_parameter_value(value)
    except TypeError:
        if isinstance(value, dict | list):
            raise RosArgumentsError(
                f"{text!r} is not a parameter value: a number, true/false, a string, or a list of "
                "one of those (e.g. [1, 2])"
            ) from None
        return text
    if value is None:
        return text
    return value


def _params_file(path_text: str) -> list[ParameterRule]:
    path = Path(path_text)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise RosArgumentsError(f"--params-file {path}: cannot read it ({error.strerror or error})") from None
    try:
        return rules_from_params_yaml(text)
    except RosArgumentsError as error:
        raise RosArgumentsError(f"--params-file {path}: {error}") from None


def rules_from_params_yaml(text: str) -> list[ParameterRule]:
    """The rules of a ROS 2 params file (``/node: {ros__parameters: {...}}``), in file order."""
    document = parse_yaml(text, RosArgumentsError)
    if not isinstance(document, dict):
        raise RosArgumentsError("expected a mapping of node names to {ros__parameters: {...}}")
    rules: list[ParameterRule] = []
    _collect_rules(document, "", rules)
    return rules


def _collect_rules(mapping: dict[Any, Any], namespace: str, rules: list[ParameterRule]) -> None:
    for key, body in mapping.items():
        node = _join_node(namespace, str(key))
        if not isinstance(body, dict):
            raise RosArgumentsError(f"{node}: expected {{{_PARAMETERS_KEY}: {{...}}}}, got {body!r}")
        if _PARAMETERS_KEY in body:
            parameters = body[_PARAMETERS_KEY] or {}
            if not isinstance(parameters, dict):
                raise RosArgumentsError(f"{node}: {_PARAMETERS_KEY} must be a mapping of names to values")
            rules.append(ParameterRule(node, _flattened(parameters, "", node)))
        else:  # a namespace: /ns: {node: {ros__parameters: ...}}
            _collect_rules(body, node, rules)


def _join_node(namespace: str, key: str) -> str:
    return f"{namespace.rstrip('/')}/{key.strip('/')}" if namespace else "/" + key.lstrip("/")


def _flattened(parameters: dict[Any, Any], prefix: str, node: str) -> dict[str, Any]:
    values: dict[str, Any] = {}
    for key, value in parameters.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            values.update(_flattened(value, name + ".", node))
            continue
        try:
            Parameter.Type.from_parameter_value(value)
        except TypeError as error:
            raise RosArgumentsError(f"{node} parameter {name!r}: {error}") from None
        values[name] = value
    return values


def _node_pattern(pattern: str) -> re.Pattern[str]:
    """ROS's node name wildcards: ``**`` any run of tokens, ``*`` one token."""
    if not pattern.startswith("/"):
        pattern = "/" + pattern
    parts = re.split(r"(\*\*|\*)", pattern)
    regex = "".join(".*" if p == "**" else "[^/]*" if p == "*" else re.escape(p) for p in parts)
    return re.compile(regex)


# -- this process's arguments -------------------------------------------------------------------

_process = RosArguments()


def set_process_ros_arguments(arguments: RosArguments) -> None:
    """The ROS arguments of this process's command line (``skydeck run``), read by every node."""
    global _process
    _process = arguments


def process_ros_arguments() -> RosArguments:
    return _process
