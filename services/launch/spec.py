"""The launch file: which processes ``skydeck launch`` starts, on which ports, with which flags.

    # The workshop system: the core, the simulator and the three workshop nodes.
    nodes:
      - name: core
        run: core            # `skydeck core`
        port_offset: 0
      - name: sim
        run: sim             # a built-in node or a path to a .py node file
        port_offset: 1
        args: ["--speed", "{speed}", "--seed", "{seed}", "--boxes", "{boxes}"]

Each node listens on ``base_port + port_offset``. Arguments and environment values may use the
placeholders ``{speed}``, ``{seed}``, each world's options (``{boxes}``, ``{robots}``,
``{obstacles}``: :func:`sim_server.worlds.world_options`) and ``{base_port}``, filled from the
launch options, and ``{name}`` for each launch argument the file declares under
``arguments:`` (:mod:`services.launch.arguments`, given as ``name:=value``); ``{{`` is a literal
brace. ``load_launch_file`` turns every problem into one
``LaunchFileError`` line that names the file and the place, e.g.
``launch.yaml: nodes[2].port_offset: Input should be greater than or equal to 0``.
"""

from __future__ import annotations

import string
from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    ValidationInfo,
    field_validator,
    model_validator,
)
from pydantic_core import ErrorDetails, PydanticCustomError

from services.builtin_nodes import BUILTIN_NODES
from services.launch.arguments import LaunchArgument, fill_arguments, substitute
from services.launch.errors import LaunchError, LaunchFileError, read_launch_text
from shared_models.text_files import parse_yaml
from sim_server.worlds import default_world, world_options  # the table only: no PyBullet

__all__ = [
    "BUILTIN_RUNS",
    "PLACEHOLDERS",
    "LaunchSpec",
    "NodeSpec",
    "default_launch_file",
    "find_launch_file",
    "load_launch_file",
    "shipped_launch_files",
]

CORE_RUN = "core"
BUILTIN_RUNS = (CORE_RUN, *BUILTIN_NODES)
"""What ``run`` may name besides a path to a .py file."""
PLACEHOLDERS = ("speed", "seed", *world_options(), "base_port")
"""The ``{name}`` placeholders that arguments and environment values may use: the launch's
options, each world's own among them (``boxes``, ``robots``: the table of worlds says)."""

# A node's name prefixes its output lines and is used by --exclude, so it stays plain tokens (a
# roslaunch file's node in a namespace is named by its graph name: robot1/talker).
_NAME_PATTERN = r"^[A-Za-z][A-Za-z0-9_-]*(/[A-Za-z][A-Za-z0-9_-]*)*$"
_RESERVED_NAMES = ("launch",)  # the supervisor's own lines start with "[launch]"
# An environment variable's or a launch argument's name (a placeholder's, so no dots or brackets).
_Identifier = Annotated[str, Field(pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")]


def _check_placeholders(text: str, info: ValidationInfo) -> str:
    # The file's declared arguments come as the validation's context (load_launch_file).
    arguments = tuple((info.context or {}).get("arguments", ()))
    try:
        fields = list(string.Formatter().parse(text))
    except ValueError as error:
        raise PydanticCustomError(
            "placeholder", f"{error} in {text!r} (write {{{{ or }}}} for a literal brace)"
        ) from None
    for _literal, field, spec, conversion in fields:
        if field is None:
            continue
        if field not in PLACEHOLDERS and field not in arguments:
            known = ", ".join(f"{{{name}}}" for name in (*PLACEHOLDERS, *arguments))
            raise PydanticCustomError(
                "placeholder",
                f"unknown placeholder {{{field}}} in {text!r}; known: {known} (or declare it under `arguments:`)",
            )
        if spec or conversion:
            raise PydanticCustomError(
                "placeholder", f"placeholders take no format or conversion: write {{{field}}}"
            )
    return text


_Template = Annotated[str, AfterValidator(_check_placeholders)]
class NodeSpec(BaseModel):
    """One process of a launch: what to run, its port offset, flags, environment and policies."""

    model_config = ConfigDict(extra="forbid", frozen=True, coerce_numbers_to_str=True)

    name: str = Field(pattern=_NAME_PATTERN, max_length=64, description="unique; prefixes output")
    package: str | None = Field(
        default=None, pattern=r"^[A-Za-z][A-Za-z0-9_]*$", description="a workspace package; run is its executable"
    )
    run: str = Field(min_length=1, description="core, a built-in node, a path to a .py file, or package's executable")
    port_offset: int = Field(ge=0, le=1000, description="the node listens on base_port + this")
    args: tuple[_Template, ...] = Field(default=(), description="extra flags; may use placeholders")
    env: dict[_Identifier, _Template] = Field(default_factory=dict, description="extra environment")
    respawn: bool = Field(default=True, description="restart the node when it dies")
    ready_timeout_s: float = Field(default=20.0, gt=0, le=600, description="time to answer /health")

    @field_validator("name")
    @classmethod
    def _not_reserved(cls, value: str) -> str:
        if value in _RESERVED_NAMES:
            raise PydanticCustomError("reserved", f"the name {value!r} is reserved; choose another")
        return value

    @field_validator("run")
    @classmethod
    def _known_run(cls, value: str, info: ValidationInfo) -> str:
        if value in BUILTIN_RUNS or value.endswith(".py") or info.data.get("package"):
            return value  # a package's executable is looked for when it runs (`skydeck run PKG EXE`)
        raise PydanticCustomError(
            "unknown_run",
            f"{value!r} is neither a built-in ({', '.join(BUILTIN_RUNS)}) nor a path to a .py file",
        )

    @property
    def is_core(self) -> bool:
        """True for the node that runs the core (``run: core``)."""
        return self.run == CORE_RUN


class LaunchSpec(BaseModel):
    """A whole launch: its declared arguments, and the nodes in start order (the core is
    started first wherever it is listed)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    arguments: dict[_Identifier, LaunchArgument] = Field(
        default_factory=dict, description="launch arguments, `name:=value` on the command line"
    )
    nodes: tuple[NodeSpec, ...]

    @field_validator("arguments")
    @classmethod
    def _not_an_option(cls, value: dict[str, LaunchArgument]) -> dict[str, LaunchArgument]:
        for name in value:
            if name in PLACEHOLDERS:
                raise PydanticCustomError(
                    "reserved", f"{name!r} is a launch option (--{name.replace('_', '-')}); choose another name"
                )
        return value

    @model_validator(mode="after")
    def _check_nodes(self) -> LaunchSpec:
        if not self.nodes:
            raise PydanticCustomError("empty", "nodes: a launch needs at least one node")
        names: dict[str, int] = {}
        offsets: dict[int, int] = {}
        cores: list[int] = []
        for index, node in enumerate(self.nodes):
            if node.name in names:
                raise PydanticCustomError(
                    "duplicate",
                    f"nodes[{index}].name: {node.name!r} is already the name of nodes[{names[node.name]}]",
                )
            if node.port_offset in offsets:
                other = self.nodes[offsets[node.port_offset]]
                raise PydanticCustomError(
                    "duplicate",
                    f"nodes[{index}].port_offset: {node.port_offset} is already used by "
                    f"nodes[{offsets[node.port_offset]}] ({other.name})",
                )
            names[node.name] = index
            offsets[node.port_offset] = index
            if node.is_core:
                cores.append(index)
        if len(cores) > 1:
            raise PydanticCustomError(
                "duplicate",
                f"nodes[{cores[1]}].run: only one node may run the core (nodes[{cores[0]}] does)",
            )
        return self

    @property
    def names(self) -> tuple[str, ...]:
        """The node names in the order listed."""
        return tuple(node.name for node in self.nodes)

    def with_arguments(self, given: Mapping[str, str]) -> LaunchSpec:
        """This launch with its arguments' ``{name}`` filled in: ``given`` (the command line's
        ``name:=value``), else the defaults. Raises ``LaunchError`` for an undeclared name or a
        required argument not given."""
        values = fill_arguments(self.arguments, given)
        nodes = tuple(
            node.model_copy(
                update={
                    "args": tuple(substitute(arg, values) for arg in node.args),
                    "env": {key: substitute(text, values) for key, text in node.env.items()},
                }
            )
            for node in self.nodes
        )
        return self.model_copy(update={"nodes": nodes})

    def uses(self, placeholder: str) -> bool:
        """Whether any node's arguments or environment use ``{placeholder}``."""
        return any(
            field == placeholder
            for node in self.nodes
            for text in (*node.args, *node.env.values())
            for _literal, field, _spec, _conversion in string.Formatter().parse(text)
        )


def default_launch_file() -> Path:
    """The default world's launch file (the table of worlds names it): the workshop system's,
    core, sim, perception, control and ai."""
    return Path(__file__).with_name(f"{default_world().launch_file}.yaml")


def shipped_launch_files() -> dict[str, Path]:
    """The launch files that ship with Skydeck, by name: ``workshop``, ``robot`` (each world's,
    as the table of worlds names them), ..."""
    return {path.stem: path for path in sorted(Path(__file__).parent.glob("*.yaml"))}


def find_launch_file(name_or_path: str | Path | None) -> Path:
    """The launch file ``skydeck launch ARG`` means: the default (the workshop) for None, a
    shipped one for a bare name (``robot``), else the path as given.

    Raises ``LaunchFileError`` for a bare name that is neither shipped nor a file here.
    """
    if name_or_path is None:
        return default_launch_file()
    path = Path(name_or_path)
    shipped = shipped_launch_files()
    if isinstance(name_or_path, str) and path.name == name_or_path and not path.suffix:
        if name_or_path in shipped:
            return shipped[name_or_path]
        if not path.exists():
            raise LaunchFileError(
                path,
                f"no such launch file, and no shipped launch of that name (shipped: {', '.join(shipped)})",
            )
    return path


def load_launch_file(path: str | Path, arguments: Mapping[str, str] | None = None) -> LaunchSpec:
    """Read and check a launch file; relative ``run`` paths are taken from the file's folder.
    With ``arguments`` (the command line's ``name:=value``; ``{}`` for none), the declared
    arguments are filled in (:meth:`LaunchSpec.with_arguments`); with None they are left as
    placeholders (``--show-args`` reads ``spec.arguments``).

    Raises ``LaunchFileError`` with one line naming the file and the problem.

        >>> spec = load_launch_file(default_launch_file())
        >>> spec.names
        ('core', 'sim', 'perception', 'control', 'ai')
    """
    path = Path(path)
    text = read_launch_text(path)
    data = parse_yaml(text, lambda reason: LaunchFileError(path, reason))
    if data is None:
        raise LaunchFileError(path, "the file is empty: expected a mapping with a `nodes:` list")
    if not isinstance(data, dict):
        raise LaunchFileError(
            path, f"expected a mapping with a `nodes:` list at the top, got a {_kind(data)}"
        )
    declared = data.get("arguments")
    context = {"arguments": tuple(declared) if isinstance(declared, dict) else ()}
    try:
        spec = LaunchSpec.model_validate(data, context=context)
    except ValidationError as error:
        raise LaunchFileError(path, _validation_problem(error)) from None
    if arguments is not None:
        try:
            spec = spec.with_arguments(arguments)
        except LaunchError as error:
            raise LaunchFileError(path, str(error)) from None
    return _resolve_paths(spec, path)


# --- helpers --------------------------------------------------------------------------------


def _resolve_paths(spec: LaunchSpec, path: Path) -> LaunchSpec:
    folder = path.resolve().parent
    nodes = []
    for index, node in enumerate(spec.nodes):
        if node.run in BUILTIN_RUNS or node.package is not None:
            nodes.append(node)
            continue
        file = (folder / node.run).resolve()
        if not file.is_file():
            raise LaunchFileError(path, f"nodes[{index}].run: no such node file {file}")
        nodes.append(node.model_copy(update={"run": str(file)}))
    return spec.model_copy(update={"nodes": tuple(nodes)})


def _validation_problem(error: ValidationError) -> str:
    errors = error.errors(include_url=False)
    first = errors[0]
    problem = _one_error(first)
    if len(errors) > 1:
        problem += f" (and {len(errors) - 1} more)"
    return problem


def _one_error(error: ErrorDetails) -> str:
    location = _location(error["loc"])
    kind = error["type"]
    value = error.get("input")
    if kind == "extra_forbidden":
        models: dict[object, type[BaseModel]] = {"nodes": NodeSpec, "arguments": LaunchArgument}
        model = LaunchSpec if len(error["loc"]) == 1 else models[error["loc"][0]]
        message = f"unknown field (allowed: {', '.join(model.model_fields)})"
    elif kind == "missing":
        message = "missing (required)"
    elif kind == "string_type" and isinstance(value, dict) and len(value) == 1:
        # YAML reads an unquoted {speed} as a mapping; say how to write it.
        name = next(iter(value))
        message = f'a placeholder must be quoted in YAML: write "{{{name}}}"'
    else:
        message = error["msg"]
    return f"{location}: {message}" if location else message


def _location(loc: tuple[int | str, ...]) -> str:
    text = ""
    for part in loc:
        if isinstance(part, int):
            text += f"[{part}]"
        else:
            text += f".{part}" if text else part
    return text


def _kind(value: Any) -> str:
    return {list: "list", str: "string", int: "number", float: "number", bool: "boolean"}.get(
        type(value), type(value).__name__
    )
