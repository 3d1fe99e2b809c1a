"""Reading a roslaunch XML file (:func:`load_roslaunch_file`): scopes (namespace, args, remaps,
environment), the ``$(...)`` substitutions, and each tag, from its elements with their line
numbers (:mod:`services.launch.roslaunch_xml`). The tags and what they become are described in
:mod:`services.launch.roslaunch`.
"""

from __future__ import annotations

import itertools
import os
import re
import shlex
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from services.launch.errors import LaunchFileError
from services.launch.ros_packages import PackageNotFound, RosPackage, find_package, package_of
from services.launch.roslaunch import RosLaunch, RosNode
from services.launch.roslaunch_xml import Element, read_xml
from services.launch.settings import LaunchSettings
from services.runtime.rosparam import check_parameter_value, parameter_tokens
from shared_models.names import InvalidNameError, resolve_name, resolve_node_name
from shared_models.text_files import parse_yaml

__all__ = ["load_roslaunch_file"]

_MAX_INCLUDE_DEPTH = 16
_SUBSTITUTION = re.compile(r"\$\(([^()]*)\)")
_IF = ("if", "unless")


# -- reading ------------------------------------------------------------------------------------

_REQUIRED = object()  # an <arg> declared with neither default nor value


@dataclass
class _Scope:
    """Where an element is read: its file, package, namespace, args, remaps and environment."""

    file: Path
    package: RosPackage | None
    namespace: str
    args: dict[str, Any]
    declared: dict[str, int]  # arg name -> the line that declared it, in this scope
    passed: dict[str, str]  # args given to this file (command line or <include>)
    used: set[str]
    remaps: list[tuple[str, str]]
    env: dict[str, str]
    depth: int = 0

    def inner(self, namespace: str) -> _Scope:
        """A ``<group>``'s scope: the same file and args, its own namespace, remaps and env."""
        return _Scope(
            self.file, self.package, namespace, dict(self.args), dict(self.declared), self.passed, self.used,
            list(self.remaps), dict(self.env), self.depth,
        )  # fmt: skip


class _Reader:
    """Reads one launch file and those it includes into nodes, parameters and warnings."""

    def __init__(self, environ: Mapping[str, str]) -> None:
        self._environ = environ  # what $(env) and $(optenv) read: the launcher's environment
        self.nodes: list[RosNode] = []
        self.parameters: list[tuple[str, Any]] = []
        self.warnings: list[str] = []
        self._anonymous: dict[str, str] = {}
        self._anonymous_ids = itertools.count(1)

    # -- errors and warnings --------------------------------------------------------------------

    @staticmethod
    def fail(scope: _Scope, element: Element, problem: str) -> LaunchFileError:
        return LaunchFileError(scope.file, f"line {element.line}: <{element.tag}>: {problem}")

    def warn(self, scope: _Scope, element: Element, problem: str) -> None:
        self.warnings.append(f"{scope.file.name}:{element.line}: <{element.tag}>: {problem}")

    def attributes(
        self, scope: _Scope, element: Element, *, required: tuple[str, ...] = (), optional: tuple[str, ...] = (),
        ignored: tuple[str, ...] = (),
    ) -> dict[str, str]:  # fmt: skip
        """The element's attributes, substituted; missing required ones fail, unknown ones warn."""
        values: dict[str, str] = {}
        for name, raw in element.attributes.items():
            if name in required or name in optional or name in _IF:
                values[name] = self.substitute(scope, element, raw)
            elif name in ignored:
                self.warn(scope, element, f"{name}={raw!r} is not used by Skydeck; ignored")
            else:
                known = ", ".join((*required, *optional, *_IF))
                self.warn(scope, element, f"unknown attribute {name!r} ignored (it takes: {known})")
        for name in required:
            if name not in values:
                raise self.fail(scope, element, f"the attribute {name!r} is required")
        return values

    def wanted(self, scope: _Scope, element: Element, values: Mapping[str, str]) -> bool:
        """Whether ``if``/``unless`` let the element through."""
        if "if" in values and "unless" in values:
            raise self.fail(scope, element, "give `if` or `unless`, not both")
        if "if" in values:
            return _boolean(values["if"], lambda: self.fail(scope, element, f"if={values['if']!r} is not true or false"))
        if "unless" in values:
            return not _boolean(
                values["unless"], lambda: self.fail(scope, element, f"unless={values['unless']!r} is not true or false")
            )
        return True

    # -- substitution -----------------------------------------------------------------------------

    def substitute(self, scope: _Scope, element: Element, text: str) -> str:
        """``text`` with its ``$(...)`` replaced (see the module docstring)."""
        return _SUBSTITUTION.sub(lambda match: self._one(scope, element, match.group(1).split()), text)

    def _one(self, scope: _Scope, element: Element, words: list[str]) -> str:
        command, arguments = (words[0], words[1:]) if words else ("", [])
        if command == "arg" and len(arguments) == 1:
            name = arguments[0]
            if name not in scope.args:
                raise self.fail(scope, element, f"$(arg {name}): no <arg name=\"{name}\"> is declared before it")
            value = scope.args[name]
            if value is _REQUIRED:
                raise self.fail(scope, element, f"$(arg {name}): the arg has no value: pass {name}:=VALUE")
            return str(value)
        if command == "find" and len(arguments) == 1:
            try:
                return str(find_package(arguments[0], scope.package).folder)
            except PackageNotFound as error:
                raise self.fail(scope, element, f"$(find {arguments[0]}): {error}") from None
        if command == "env" and len(arguments) == 1:
            if arguments[0] not in self._environ:
                raise self.fail(scope, element, f"$(env {arguments[0]}): the variable is not set (use $(optenv ...))")
            return self._environ[arguments[0]]
        if command == "optenv" and arguments:
            return self._environ.get(arguments[0], " ".join(arguments[1:]))
        if command == "dirname" and not arguments:
            return str(scope.file.parent)
        if command == "anon" and len(arguments) == 1:
            key = arguments[0]
            if key not in self._anonymous:
                self._anonymous[key] = f"{key}_{os.getpid()}_{next(self._anonymous_ids)}"
            return self._anonymous[key]
        if command == "eval":
            raise self.fail(scope, element, "$(eval ...) is not provided by Skydeck: use $(arg ...) and if/unless")
        known = "$(arg NAME), $(find PKG), $(env VAR), $(optenv VAR DEFAULT), $(dirname), $(anon NAME)"
        raise self.fail(scope, element, f"$({' '.join(words)}) is not a substitution Skydeck knows ({known})")

    # -- the tags -------------------------------------------------------------------------------

    def read_file(self, scope: _Scope) -> None:
        root = read_xml(scope.file)
        self.attributes(scope, root, ignored=("deprecated",))
        self.read_children(scope, root)
        unused = sorted(set(scope.passed) - scope.used)
        if unused:
            raise LaunchFileError(
                scope.file, f"{', '.join(unused)}: given but not declared here (no <arg name=\"{unused[0]}\">)"
            )

    def read_children(self, scope: _Scope, parent: Element) -> None:
        handlers = {
            "arg": self.read_arg,
            "param": self.read_param,
            "rosparam": self.read_rosparam,
            "node": self.read_node,
            "group": self.read_group,
            "include": self.read_include,
            "remap": self.read_remap,
            "env": self.read_env,
            "machine": self.skip,
            "test": self.skip,
        }
        for element in parent.children:
            handler = handlers.get(element.tag)
            if handler is None:
                raise self.fail(scope, element, f"not a tag Skydeck knows here (it reads: {', '.join(handlers)})")
            handler(scope, element)

    def skip(self, scope: _Scope, element: Element) -> None:
        what = "tests are not run" if element.tag == "test" else "every node runs on this machine"
        self.warn(scope, element, f"skipped: {what} by skydeck launch")

    def read_arg(self, scope: _Scope, element: Element) -> None:
        values = self.attributes(scope, element, required=("name",), optional=("default", "value", "doc"))
        if not self.wanted(scope, element, values):
            return
        name = values["name"]
        if name in scope.declared:
            raise self.fail(scope, element, f"arg {name} is declared twice (first on line {scope.declared[name]})")
        scope.declared[name] = element.line
        if "default" in values and "value" in values:
            raise self.fail(scope, element, f"arg {name}: give default= (settable) or value= (fixed), not both")
        if name in scope.passed:
            scope.used.add(name)
            if "value" in values:
                raise self.fail(scope, element, f"arg {name} has a fixed value= and cannot be set from outside")
            scope.args[name] = scope.passed[name]
        else:
            scope.args[name] = values.get("value", values.get("default", _REQUIRED))

    def read_param(self, scope: _Scope, element: Element, private: str | None = None) -> None:
        values = self.attributes(
            scope, element, required=("name",), optional=("value", "type", "textfile", "binfile", "command")
        )
        if not self.wanted(scope, element, values):
            return
        sources = [key for key in ("value", "textfile", "binfile", "command") if key in values]
        if len(sources) != 1:
            raise self.fail(scope, element, f"param {values['name']}: give exactly one of value=, textfile= (got {len(sources)})")
        if sources[0] in ("binfile", "command"):
            raise self.fail(scope, element, f"{sources[0]}= is not provided by Skydeck: give value= or textfile=")
        name = self.parameter_name(scope, element, values["name"], private)
        if sources[0] == "textfile":
            value: Any = self.read_text(scope, element, values["textfile"], "textfile")
        else:
            value = self.typed(scope, element, values["value"], values.get("type", "auto"))
        self.set_parameter(scope, element, name, value)

    def read_text(self, scope: _Scope, element: Element, name: str, attribute: str) -> str:
        """The text of the file ``name`` (relative to the launch file's folder)."""
        path = Path(name)
        path = path if path.is_absolute() else scope.file.parent / path
        try:
            return path.read_text(encoding="utf-8")
        except OSError as error:
            raise self.fail(scope, element, f"{attribute} {path}: cannot read it ({error.strerror or error})") from None

    def typed(self, scope: _Scope, element: Element, text: str, kind: str) -> Any:
        """A ``<param value>`` read as its ``type`` says (``auto``: bool, int, double or str)."""
        try:
            if kind == "str" or kind == "string":
                return text
            if kind == "int":
                return int(text.strip())
            if kind == "double":
                return float(text.strip())
            if kind == "bool" or kind == "boolean":
                return _boolean(text, lambda: ValueError(f"{text!r} is not true or false"))
            if kind == "yaml":
                return yaml.safe_load(text)
        except (ValueError, yaml.YAMLError) as error:
            raise self.fail(scope, element, f"value {text!r} is not of type {kind}: {error}") from None
        if kind != "auto":
            raise self.fail(scope, element, f"type {kind!r} is not one of str, int, double, bool, yaml, auto")
        stripped = text.strip()
        if stripped.lower() in ("true", "false"):
            return stripped.lower() == "true"
        for number in (int, float):
            try:
                return number(stripped)
            except ValueError:
                pass
        return text

    def read_rosparam(self, scope: _Scope, element: Element, private: str | None = None) -> None:
        values = self.attributes(scope, element, optional=("command", "file", "param", "ns", "subst_value"))
        if not self.wanted(scope, element, values):
            return
        command = values.get("command", "load")
        if command != "load":
            raise self.fail(scope, element, f"command={command!r} is not provided by Skydeck (it loads parameters only)")
        if "file" in values:
            text = self.read_text(scope, element, values["file"], "file")
        else:
            text = element.text
        if "subst_value" in values and _boolean(values["subst_value"], lambda: self.fail(scope, element, "subst_value is not true or false")):
            text = self.substitute(scope, element, text)
        data = parse_yaml(text, lambda reason: self.fail(scope, element, f"its text: {reason}")) if text.strip() else None
        base = self.parameter_name(scope, element, values["ns"], private) if "ns" in values else None
        if "param" in values:
            name = self.parameter_name(scope, element, values["param"], private, namespace=base)
            self.set_parameter(scope, element, name, data)
            return
        if data is None:
            return
        if not isinstance(data, dict):
            raise self.fail(scope, element, "without param=, the YAML must be a mapping of names to values")
        namespace = base or self.parameter_name(scope, element, "~" if private else ".", private)
        for name, value in _leaves(data, namespace.rstrip("/")):
            self.set_parameter(scope, element, name or "/", value)

    def parameter_name(
        self, scope: _Scope, element: Element, name: str, private: str | None, *, namespace: str | None = None
    ) -> str:
        """An absolute parameter name: relative ones in the namespace (a node's own, for its
        private parameters), ``~name`` only inside a ``<node>``."""
        if name == ".":
            name = ""
        if name.startswith("~"):
            if private is None:
                raise self.fail(scope, element, f"{name}: a private name (~) only means something inside a <node>")
            name, base = name[1:].lstrip("/"), private
        elif name.startswith("/"):
            base = "/"
        else:
            base = namespace or private or scope.namespace
        full = "/" + "/".join(part for part in (*base.split("/"), *name.split("/")) if part)
        try:
            parameter_tokens(full)
        except ValueError as error:
            raise self.fail(scope, element, str(error)) from None
        return full

    def set_parameter(self, scope: _Scope, element: Element, name: str, value: Any) -> None:
        try:
            check_parameter_value(value, name)
        except ValueError as error:
            raise self.fail(scope, element, str(error)) from None
        self.parameters.append((name, value))

    def read_remap(self, scope: _Scope, element: Element, node: list[tuple[str, str]] | None = None) -> None:
        values = self.attributes(scope, element, required=("from", "to"))
        if self.wanted(scope, element, values):
            (scope.remaps if node is None else node).append((values["from"], values["to"]))

    def read_env(self, scope: _Scope, element: Element, node: dict[str, str] | None = None) -> None:
        values = self.attributes(scope, element, required=("name", "value"))
        if self.wanted(scope, element, values):
            (scope.env if node is None else node)[values["name"]] = values["value"]

    def read_group(self, scope: _Scope, element: Element) -> None:
        values = self.attributes(scope, element, optional=("ns",), ignored=("clear_params",))
        if self.wanted(scope, element, values):
            self.read_children(scope.inner(self.namespace(scope, element, values.get("ns", ""))), element)

    def namespace(self, scope: _Scope, element: Element, ns: str) -> str:
        """The namespace ``ns=`` makes: relative to the scope's, or absolute."""
        if not ns:
            return scope.namespace
        if ns.strip("/") == "":
            return "/"
        try:
            return resolve_name(ns.rstrip("/"), scope.namespace)
        except InvalidNameError as error:
            raise self.fail(scope, element, f"ns={ns!r}: {error}") from None

    def read_include(self, scope: _Scope, element: Element) -> None:
        values = self.attributes(scope, element, required=("file",), optional=("ns", "pass_all_args"), ignored=("clear_params",))
        if not self.wanted(scope, element, values):
            return
        path = Path(values["file"])
        path = (path if path.is_absolute() else scope.file.parent / path).resolve()
        if not path.is_file():
            raise self.fail(scope, element, f"no such file {path}")
        if scope.depth >= _MAX_INCLUDE_DEPTH:
            raise self.fail(scope, element, f"includes nest deeper than {_MAX_INCLUDE_DEPTH}: does a file include itself?")
        passed: dict[str, str] = {}
        if "pass_all_args" in values and _boolean(values["pass_all_args"], lambda: self.fail(scope, element, "pass_all_args is not true or false")):
            passed = {name: str(value) for name, value in scope.args.items() if value is not _REQUIRED}
        inner = _Scope(
            path, package_of(path) or scope.package, self.namespace(scope, element, values.get("ns", "")), {}, {},
            passed, set(), list(scope.remaps), dict(scope.env), scope.depth + 1,
        )  # fmt: skip
        for child in element.children:
            if child.tag == "arg":
                arg = self.attributes(scope, child, required=("name",), optional=("value", "default", "doc"))
                if "value" not in arg and "default" not in arg:
                    raise self.fail(scope, child, f"arg {arg['name']}: an <include> passes it with value=")
                if self.wanted(scope, child, arg):
                    passed[arg["name"]] = arg.get("value", arg.get("default", ""))
            elif child.tag == "env":
                self.read_env(scope, child, inner.env)
            else:
                raise self.fail(scope, child, "an <include> holds <arg> and <env> only")
        if "pass_all_args" in values:  # passing all: those the included file does not declare are fine
            inner.used.update(passed)
        self.read_file(inner)

    def read_node(self, scope: _Scope, element: Element) -> None:
        values = self.attributes(
            scope, element, required=("name", "pkg", "type"), optional=("args", "ns", "respawn", "output"),
            ignored=("respawn_delay", "required", "clear_params", "cwd", "launch-prefix", "machine"),
        )  # fmt: skip
        if not self.wanted(scope, element, values):
            return
        try:
            node_name = resolve_node_name(values["name"]).lstrip("/")
        except InvalidNameError as error:
            raise self.fail(scope, element, str(error)) from None
        namespace = self.namespace(scope, element, values.get("ns", ""))
        full_name = f"{namespace.rstrip('/')}/{node_name}"
        if any(node.name == full_name for node in self.nodes):
            raise self.fail(scope, element, f"a second node named {full_name} (names are unique in a launch)")
        if values.get("output", "screen") not in ("screen", "log"):
            self.warn(scope, element, f"output={values['output']!r}: expected screen or log; output is shown either way")
        try:
            program = find_package(values["pkg"], scope.package).program(values["type"])
        except PackageNotFound as error:
            raise self.fail(scope, element, str(error)) from None
        if program.suffix != ".py":
            raise self.fail(scope, element, f"type {values['type']}: Skydeck runs Python nodes (a .py file); {program} is not one")
        remaps = list(scope.remaps)
        env = dict(scope.env)
        private = full_name
        for child in element.children:
            if child.tag == "param":
                self.read_param(scope, child, private)
            elif child.tag == "rosparam":
                self.read_rosparam(scope, child, private)
            elif child.tag == "remap":
                self.read_remap(scope, child, remaps)
            elif child.tag == "env":
                self.read_env(scope, child, env)
            else:
                raise self.fail(scope, child, "a <node> holds <param>, <rosparam>, <remap> and <env> only")
        try:
            args = shlex.split(values.get("args", ""))
        except ValueError as error:
            raise self.fail(scope, element, f"args: {error}") from None
        ros_args = [f"{source}:={target}" for source, target in remaps] + [f"__name:={node_name}"]
        if namespace != "/":
            ros_args.append(f"__ns:={namespace}")
        respawn = values.get("respawn", "false")
        self.nodes.append(
            RosNode(
                name=full_name,
                program=program,
                args=(*args, *ros_args),
                env=tuple(env.items()),
                respawn=_boolean(respawn, lambda: self.fail(scope, element, f"respawn={respawn!r} is not true or false")),
                place=f"line {element.line}",
            )
        )


def _boolean(text: str, error: Any) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise error()


def _leaves(data: dict[str, Any], prefix: str) -> list[tuple[str, Any]]:
    """A YAML mapping as (name, value) pairs, merged into the namespace as ``rosparam load`` does:
    nested mappings by their leaves, an empty mapping as itself."""
    pairs: list[tuple[str, Any]] = []
    for key, value in data.items():
        name = f"{prefix}/{key}"
        if isinstance(value, dict) and value:
            pairs += _leaves(value, name)
        else:
            pairs.append((name, value))
    return pairs


def load_roslaunch_file(
    path: str | Path, args: Mapping[str, str] | None = None, *, environ: Mapping[str, str] | None = None
) -> RosLaunch:
    """Read a roslaunch file, with ``args`` as its command line's ``name:=value`` and
    ``environ`` for its ``$(env NAME)`` (default: the launcher's, :class:`LaunchSettings`).

    Raises ``LaunchFileError`` with one line naming the file, the line and the problem.
    """
    path = Path(path).resolve() if Path(path).exists() else Path(path)
    reader = _Reader(environ if environ is not None else LaunchSettings().environment)
    reader.read_file(_Scope(path, package_of(path), "/", {}, {}, dict(args or {}), set(), [], {}))
    return RosLaunch(path, tuple(reader.nodes), tuple(reader.parameters), tuple(reader.warnings))
