"""ROS 2's XML and YAML launch files, read into the same actions a Python launch file makes.

    <launch>                                      launch:
      <arg name="rate" default="10"/>             - arg: {name: rate, default: "10"}
      <let name="ns" value="robot1"/>             - let: {name: ns, value: robot1}
      <include file="$(find-pkg-share p)/launch/more.launch.py">
        <arg name="x" value="1"/>                 - include: {file: ..., arg: [{name: x, value: "1"}]}
      </include>
      <group>                                     - group:
        <push_ros_namespace namespace="r1"/>          - push_ros_namespace: {namespace: r1}
        <node pkg="p" exec="talker" name="t" namespace="ns" args="--fast" output="screen">
          <param name="rate" value="$(var rate)"/>    - node: {pkg: p, exec: talker, name: t,
          <param from="$(find-pkg-share p)/config/params.yaml"/>   param: [{name: rate, value: ...}],
          <remap from="chatter" to="news"/>              remap: [{from: chatter, to: news}]}
        </node>
      </group>
    </launch>

Every tag takes ``if``/``unless``; a group is scoped unless ``scoped="false"``. Substitutions:
``$(var NAME)``, ``$(find-pkg-share PKG)``, ``$(env NAME [DEFAULT])``, ``$(dirname)``. A tag,
attribute or substitution Skydeck does not provide is one line naming it and its line; an
attribute that changes nothing here (``output``) is accepted.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from services.launch.errors import read_launch_text
from services.launch.ros2.actions import (
    Action,
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    LaunchDescription,
    LaunchDescriptionSource,
    Node,
    PushRosNamespace,
    SetLaunchConfiguration,
)
from services.launch.ros2.places import Place
from services.launch.ros2.substitutions import (
    EnvironmentVariable,
    FindPackageShare,
    IfCondition,
    LaunchConfiguration,
    Substitution,
    TextSubstitution,
    ThisLaunchFileDir,
    UnlessCondition,
)
from services.launch.roslaunch_xml import Element, read_xml
from shared_models.text_files import parse_yaml

__all__ = ["load_markup"]

_SUBSTITUTION = re.compile(r"\$\(([^()]*)\)")
_CONDITIONS = ("if", "unless")


@dataclass(frozen=True)
class _Tag:
    required: tuple[str, ...]
    optional: tuple[str, ...] = ()
    harmless: tuple[str, ...] = ()  # accepted, changes nothing under Skydeck
    children: tuple[str, ...] = ()


_TAGS = {
    "arg": _Tag(("name",), ("default", "description"), children=("choice",)),
    "let": _Tag(("name", "value")),
    "include": _Tag(("file",), children=("arg",)),
    "group": _Tag((), ("scoped",), ("forwarding",)),
    "push_ros_namespace": _Tag(("namespace",)),
    "node": _Tag(
        ("pkg", "exec"), ("name", "namespace", "args", "ros_args", "respawn"),
        ("output", "emulate_tty", "respawn_delay", "exec_name", "log_cmd"), ("param", "remap", "env"),
    ),  # fmt: skip
}


def load_markup(path: Path, kind: str) -> LaunchDescription:
    """The actions of a ROS 2 XML (``kind="xml"``) or YAML (``"yaml"``) launch file."""
    root = read_xml(path) if kind == "xml" else _read_yaml(path)
    description = LaunchDescription()
    description.entities = [_action(element, path) for element in root.children]
    return description


# -- actions ------------------------------------------------------------------------------------


def _action(element: Element, path: Path) -> Action:
    place = Place(path, element.line)
    tag = element.tag.replace("-", "_")
    spec = _TAGS.get(tag)
    if spec is None:
        raise place.error(f"<{element.tag}> is not provided by Skydeck (it reads: {', '.join(_TAGS)})")
    values = _attributes(element, spec, place)
    if tag == "group":
        action: Action = GroupAction(
            [_action(child, path) for child in element.children], scoped=_flag(values.get("scoped"), True, place)
        )
    else:
        for child in element.children:
            if child.tag not in spec.children:
                raise Place(path, child.line).error(f"<{child.tag}> inside <{element.tag}> is not provided by Skydeck")
        action = _leaf(tag, values, element, path, place)
    action.place = place
    if "if" in values or "unless" in values:
        if "if" in values and "unless" in values:
            raise place.error("give `if` or `unless`, not both")
        condition = IfCondition(values["if"]) if "if" in values else UnlessCondition(values["unless"])
        condition.place = place
        action.condition = condition
    return action


def _leaf(tag: str, values: dict[str, Any], element: Element, path: Path, place: Place) -> Action:
    if tag == "arg":
        choices = [_attributes(c, _Tag(("value",)), Place(path, c.line))["value"] for c in element.children]
        default = values.get("default")
        return DeclareLaunchArgument(
            _plain(element, "name", place), default_value=default,
            description=element.attributes.get("description", ""),
            choices=[_plain_text(c, place) for c in choices] if choices else None,
        )  # fmt: skip
    if tag == "let":
        return SetLaunchConfiguration(values["name"], values["value"])
    if tag == "include":
        arguments = []
        for child in element.children:
            given = _attributes(child, _Tag(("name", "value")), Place(path, child.line))
            arguments.append((given["name"], given["value"]))
        source = LaunchDescriptionSource(values["file"])
        source.place = place
        return IncludeLaunchDescription(source, launch_arguments=arguments)
    if tag == "push_ros_namespace":
        return PushRosNamespace(values["namespace"])
    return _node(values, element, path, place)


def _node(values: dict[str, Any], element: Element, path: Path, place: Place) -> Node:
    parameters: list[Any] = []
    param_places: list[Place] = []
    remappings: list[tuple[Any, Any]] = []
    env: dict[Any, Any] = {}
    for child in element.children:
        where = Place(path, child.line)
        if child.tag == "param":
            if "from" in child.attributes:
                parameters.append(_attributes(child, _Tag(("from",)), where)["from"])
            else:
                given = _attributes(child, _Tag(("name", "value")), where)
                parameters.append({_plain_text(given["name"], where): given["value"]})
            param_places.append(where)
        elif child.tag == "remap":
            given = _attributes(child, _Tag(("from", "to")), where)
            remappings.append((given["from"], given["to"]))
        else:
            given = _attributes(child, _Tag(("name", "value")), where)
            env[_plain_text(given["name"], where)] = given["value"]
    node = Node(
        package=values["pkg"], executable=values["exec"], name=values.get("name"), namespace=values.get("namespace"),
        parameters=parameters, remappings=remappings, additional_env=env,
        arguments=_words(element.attributes.get("args", ""), values.get("args")),
        ros_arguments=_words(element.attributes.get("ros_args", ""), values.get("ros_args")),
        respawn=values.get("respawn", False),
    )  # fmt: skip
    node.param_places = param_places
    return node


def _words(raw: str, value: Any) -> list[Any]:
    """``args="a b $(var c)"``: one argument per word (a word's substitutions stay in it)."""
    if value is None:
        return []
    return [_substitutions(word, value[0].place) for word in _split(raw)]


def _split(text: str) -> list[str]:
    """Words split at spaces outside ``$(...)``."""
    words: list[str] = []
    word, depth = "", 0
    for index, char in enumerate(text):
        if char == "(" and text[index - 1 : index] == "$":
            depth += 1
        elif char == ")" and depth:
            depth -= 1
        if char.isspace() and not depth:
            if word:
                words.append(word)
            word = ""
        else:
            word += char
    return [*words, word] if word else words


# -- attributes and substitutions --------------------------------------------------------------


def _attributes(element: Element, spec: _Tag, place: Place) -> dict[str, Any]:
    values: dict[str, Any] = {}
    for name, raw in element.attributes.items():
        if name in spec.harmless:
            continue
        if name not in spec.required and name not in spec.optional and name not in _CONDITIONS:
            raise place.error(f"<{element.tag} {name}=...> is not provided by Skydeck")
        values[name] = _substitutions(raw, place)
    for name in spec.required:
        if name not in values:
            raise place.error(f"<{element.tag}> needs the attribute {name!r}")
    return values


def _substitutions(text: str, place: Place) -> list[Substitution]:
    """``text`` as substitutions: its ``$(...)`` and the plain text between them."""
    parts: list[Substitution] = []
    position = 0
    for match in _SUBSTITUTION.finditer(text):
        if match.start() > position:
            parts.append(TextSubstitution(text=text[position : match.start()]))
        parts.append(_one(match.group(1).split(), place))
        position = match.end()
    if position < len(text) or not parts:
        parts.append(TextSubstitution(text=text[position:]))
    for part in parts:
        part.place = place
    return parts


def _one(words: list[str], place: Place) -> Substitution:
    command, arguments = (words[0], words[1:]) if words else ("", [])
    if command == "var" and len(arguments) == 1:
        return LaunchConfiguration(arguments[0])
    if command == "find-pkg-share" and len(arguments) == 1:
        return FindPackageShare(arguments[0])
    if command == "env" and len(arguments) in (1, 2):
        return EnvironmentVariable(arguments[0], default_value=arguments[1] if len(arguments) == 2 else None)
    if command == "dirname" and not arguments:
        return ThisLaunchFileDir()
    raise place.error(f"$({' '.join(words)}) is not provided by Skydeck (it has $(var), $(find-pkg-share), $(env), $(dirname))")


def _plain_text(value: list[Substitution], place: Place) -> str:
    if not all(isinstance(part, TextSubstitution) for part in value):
        raise place.error("a name or a choice is plain text here (no $(...))")
    return "".join(part.text for part in value if isinstance(part, TextSubstitution))


def _plain(element: Element, name: str, place: Place) -> str:
    text = element.attributes.get(name, "")
    if "$(" in text:
        raise place.error(f"<{element.tag}>'s {name} is plain text (no $(...))")
    return text


def _flag(value: list[Substitution] | None, default: bool, place: Place) -> bool:
    if value is None:
        return default
    text = _plain_text(value, place).lower()
    if text not in ("true", "false"):
        raise place.error(f"scoped={text!r} is not true or false")
    return text == "true"


# -- YAML ---------------------------------------------------------------------------------------


def _read_yaml(path: Path) -> Element:
    """A ROS 2 YAML launch file as the elements its XML would have (lines kept)."""
    document = parse_yaml(
        read_launch_text(path), lambda reason: Place(path, reason.line).error(f"YAML syntax error: {reason.problem}"), nodes=True
    )
    if not isinstance(document, yaml.MappingNode):
        raise Place(path).error("expected a mapping with a `launch:` list at the top")
    for key, value in document.value:
        if key.value == "launch":
            if not isinstance(value, yaml.SequenceNode):
                raise Place(path, value.start_mark.line + 1).error("`launch:` is a list of actions (- node: ...)")
            return Element("launch", {}, 1, [_yaml_entity(item, path) for item in value.value])
    raise Place(path).error("no `launch:` list at the top")


def _yaml_entity(node: yaml.Node, path: Path) -> Element:
    place = Place(path, node.start_mark.line + 1)
    if not isinstance(node, yaml.MappingNode) or len(node.value) != 1:
        raise place.error("each action is a mapping with one key (- node: {...}, - arg: {...})")
    key, body = node.value[0]
    tag = str(key.value)
    element = Element(tag, {}, place.line)
    if isinstance(body, yaml.SequenceNode):  # `- group: [ ...actions ]`
        element.children = [_yaml_entity(item, path) for item in body.value]
        return element
    if isinstance(body, yaml.ScalarNode) and body.value in ("", "~", "null"):
        return element
    if not isinstance(body, yaml.MappingNode):
        raise place.error(f"`{tag}:` takes a mapping of its attributes")
    for name_node, value in body.value:
        name = str(name_node.value)
        if isinstance(value, yaml.SequenceNode) and name == "children":
            element.children += [_yaml_entity(item, path) for item in value.value]
        elif isinstance(value, yaml.SequenceNode) and name in ("param", "remap", "env", "arg", "choice"):
            element.children += [_yaml_child(name, item, path) for item in value.value]
        else:
            element.attributes[name] = _yaml_text(value, Place(path, value.start_mark.line + 1))
    return element


def _yaml_child(tag: str, node: yaml.Node, path: Path) -> Element:
    place = Place(path, node.start_mark.line + 1)
    if not isinstance(node, yaml.MappingNode):
        raise place.error(f"each `{tag}` is a mapping ({{name: ..., value: ...}})")
    attributes = {str(key.value): _yaml_text(value, place) for key, value in node.value}
    return Element(tag, attributes, place.line)


def _yaml_text(node: yaml.Node, place: Place) -> str:
    """A value as the text its XML attribute would hold (a list as YAML's flow text)."""
    if isinstance(node, yaml.ScalarNode):
        return str(node.value)
    if isinstance(node, yaml.SequenceNode) and all(isinstance(item, yaml.ScalarNode) for item in node.value):
        return "[" + ", ".join(str(item.value) for item in node.value) + "]"
    raise place.error("a value here is text, a number or a list of them")
