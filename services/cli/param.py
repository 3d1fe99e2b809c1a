"""``skydeck param list | get | set | describe | dump | load`` (ros2 param), through the core's
gateway to the node's parameter services (``/NODE/list_parameters``...)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from services.cli.arguments import add_noun, add_verb, node_name
from services.cli.core_client import error_detail, get_json, post_json
from services.cli.errors import CliError
from services.cli.formatting import to_yaml

__all__ = ["add_parser"]

_TIMEOUT_S = 10.0


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    verbs = add_noun(subparsers, "param", "list, get, set, dump and load node parameters")

    p = add_verb(verbs, "list", _list, "the parameter names of a node (of every node without NODE)")
    p.add_argument("node", nargs="?")
    p.add_argument("-t", "--param-type", action="store_true", help="show each parameter's type")
    p.add_argument("--param-prefixes", nargs="+", default=[], metavar="PREFIX", help="only names under these")

    p = add_verb(verbs, "get", _get, "a parameter's value", "node", "name")
    p.add_argument("--hide-type", action="store_true", help="print the value only")

    add_verb(verbs, "set", _set, "set a parameter (VALUE as YAML: 0.5, true, robot1, [1, 2])", "node", "name", "value")

    p = add_verb(verbs, "describe", _describe, "type, description and constraints of parameters", "node")
    p.add_argument("names", nargs="+", metavar="name")

    add_verb(verbs, "dump", _dump, "a node's parameters as a ROS 2 params file (YAML)", "node")

    add_verb(verbs, "load", _load, "set a node's parameters from a ROS 2 params file", "node", "file")


def _call(node: str, verb: str, body: dict[str, Any]) -> dict[str, Any]:
    """Call ``NODE/VERB`` through the core; a node without parameter services is one clear line."""
    reply = post_json(f"{node}/{verb}", body, timeout_s=_TIMEOUT_S)
    if reply.status == 404:
        raise CliError(f"no node {node} with parameters: see `skydeck node list` (or `skydeck param list`)")
    if reply.status != 200:
        raise CliError(f"{node}/{verb}: {error_detail(reply)} (HTTP {reply.status})")
    return reply.json()  # type: ignore[no-any-return]


def _names(node: str, prefixes: list[str]) -> list[str]:
    return _call(node, "list_parameters", {"prefixes": prefixes})["result"]["names"]  # type: ignore[no-any-return]


def _values(node: str, names: list[str]) -> list[dict[str, Any]]:
    return _call(node, "get_parameters", {"names": names})["values"]  # type: ignore[no-any-return]


def _list(args: argparse.Namespace) -> int:
    if args.node:
        nodes = [node_name(args.node)]
    else:  # every node that serves parameters, as the graph says
        graph = get_json("/api/graph")
        services = {s["name"] for s in graph["services"]}
        nodes = sorted(n["name"] for n in graph["nodes"] if f"{n['name']}/list_parameters" in services)
    for node in nodes:
        names = _names(node, args.param_prefixes)
        if not args.node:
            print(f"{node}:")
        types = _call(node, "describe_parameters", {"names": names})["descriptors"] if args.param_type else []
        for i, name in enumerate(names):
            print(f"  {name}" + (f" (type: {_type_label(types[i]['type'])})" if args.param_type else ""))
    return 0


def _get(args: argparse.Namespace) -> int:
    from services.runtime.parameter import Parameter, parameter_value_to_python
    from shared_models.rcl_interfaces import ParameterValue

    node = node_name(args.node)
    value = ParameterValue.model_validate(_values(node, [args.name])[0])
    if value.type == Parameter.Type.NOT_SET:
        raise CliError(f"{node} has no value for parameter {args.name!r}: see `skydeck param list {node}`")
    python = parameter_value_to_python(value)
    if isinstance(python, bytes):
        python = list(python)
    if args.hide_type:
        print(python)
    else:
        type_ = Parameter.Type(value.type)
        print(f"{_type_label(type_).split()[0].capitalize()} value{'s are' if type_.is_array else ' is'}: {python}")
    return 0


def _set(args: argparse.Namespace) -> int:
    from services.runtime.ros_args import RosArgumentsError, parameter_value

    node = node_name(args.node)
    try:
        value = parameter_value(args.value)
    except RosArgumentsError as error:
        raise CliError(f"VALUE {error}") from None
    result = _set_values(node, {args.name: value})[0]
    if not result["successful"]:
        raise CliError(f"setting parameter failed: {result['reason']}")
    print("Set parameter successful")
    return 0


def _set_values(node: str, values: dict[str, Any]) -> list[dict[str, Any]]:
    from services.runtime.parameter import Parameter

    try:
        messages = [Parameter(name, value=value).to_parameter_msg().model_dump(mode="json") for name, value in values.items()]
    except (TypeError, ValueError) as error:
        raise CliError(str(error)) from None
    return _call(node, "set_parameters", {"parameters": messages})["results"]  # type: ignore[no-any-return]


def _describe(args: argparse.Namespace) -> int:
    node = node_name(args.node)
    for descriptor in _call(node, "describe_parameters", {"names": args.names})["descriptors"]:
        print(f"Parameter name: {descriptor['name']}")
        print(f"  Type: {_type_label(descriptor['type'])}")
        if descriptor["description"]:
            print(f"  Description: {descriptor['description']}")
        constraints = [f"Read only: {str(descriptor['read_only']).lower()}"] if descriptor["read_only"] else []
        if descriptor["dynamic_typing"]:
            constraints.append("Dynamic typing: true")
        for bounds in descriptor["floating_point_range"] + descriptor["integer_range"]:
            constraints += [f"Min value: {bounds['from_value']}", f"Max value: {bounds['to_value']}"]
            if bounds["step"]:
                constraints.append(f"Step: {bounds['step']}")
        if descriptor["additional_constraints"]:
            constraints.append(descriptor["additional_constraints"])
        if constraints:
            print("  Constraints:\n" + "\n".join(f"    {line}" for line in constraints))
    return 0


def _dump(args: argparse.Namespace) -> int:
    from services.runtime.parameter import parameter_value_to_python
    from shared_models.rcl_interfaces import ParameterValue

    node = node_name(args.node)
    names = _names(node, [])
    tree: dict[str, Any] = {}
    for name, raw in zip(names, _values(node, names), strict=True):
        value = parameter_value_to_python(ParameterValue.model_validate(raw))
        if value is None:
            continue  # declared without a value: nothing to dump
        *namespaces, last = name.split(".")
        branch = tree
        for part in namespaces:
            branch = branch.setdefault(part, {})
        branch[last] = list(value) if isinstance(value, bytes) else value
    print(to_yaml({node: {"ros__parameters": tree}}))
    return 0


def _load(args: argparse.Namespace) -> int:
    from services.runtime.ros_args import RosArgumentsError, rules_from_params_yaml

    node = node_name(args.node)
    path = Path(args.file)
    try:
        rules = rules_from_params_yaml(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise CliError(f"cannot read {path}: {error.strerror or error}") from None
    except RosArgumentsError as error:
        raise CliError(f"{path}: {error}") from None
    values: dict[str, Any] = {}
    for rule in rules:
        if rule.matches(node):
            values.update(rule.values)
    if not values:
        raise CliError(f"{path} has no parameters for {node} (expected a key {node}: or /**:)")
    for name in _unchanged_read_only(node, values):
        print(f"Parameter {name} is read-only and unchanged: skipped")
        del values[name]
    failed = 0
    for name, result in zip(values, _set_values(node, values), strict=True):
        if result["successful"]:
            print(f"Set parameter {name} successful")
        else:
            failed += 1
            print(f"Set parameter {name} failed: {result['reason']}")
    if failed:
        raise CliError(f"{failed} of {len(values)} parameters were refused by {node}")
    return 0


def _unchanged_read_only(node: str, values: dict[str, Any]) -> list[str]:
    """Read-only parameters the file gives their current value (a dump loaded back)."""
    from services.runtime.parameter import parameter_value_to_python
    from shared_models.rcl_interfaces import ParameterValue

    names = list(values)
    descriptors = _call(node, "describe_parameters", {"names": names})["descriptors"]
    read_only = [name for name, d in zip(names, descriptors, strict=True) if d["read_only"]]
    current = _values(node, read_only) if read_only else []
    return [
        name
        for name, raw in zip(read_only, current, strict=True)
        if parameter_value_to_python(ParameterValue.model_validate(raw)) == values[name]
    ]


def _type_label(type_number: int) -> str:
    from services.runtime.parameter import Parameter

    try:
        return Parameter.Type(type_number).label
    except ValueError:
        return f"unknown type {type_number}"
