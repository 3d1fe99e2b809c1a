"""An ament_python package's executables, read from ``setup.py`` or ``setup.cfg`` without running them.

``ros2 run PKG NAME`` runs the console script ``NAME`` that colcon installed from the package's
entry points::

    setup(..., entry_points={"console_scripts": ["turtle_circle = my_pkg.circle:main"]})

``setup.py`` is read as Python syntax (``ast``) and never executed: a course's file is a plain
call to ``setup`` whose arguments are literals, with at most a ``package_name = "my_pkg"`` used
in them (``f"{package_name}.circle:main"``, ``package_name + ".circle:main"``), which is what is
understood here. ``setup.cfg``'s ``[options.entry_points]`` is read with configparser.
"""

from __future__ import annotations

import ast
import configparser
from pathlib import Path
from typing import Any

from services.ros.errors import RosFacadeError

__all__ = ["EntryPoint", "SetupFileError", "console_scripts"]


class SetupFileError(RosFacadeError):
    """A package's setup.py or setup.cfg cannot be read for its entry points."""


class EntryPoint:
    """One console script: ``name = module:function``."""

    def __init__(self, name: str, module: str, function: str) -> None:
        self.name = name
        self.module = module
        self.function = function

    @classmethod
    def parse(cls, spec: str, where: str) -> EntryPoint:
        name, equals, target = spec.partition("=")
        module, colon, function = target.strip().partition(":")
        function = function.split("[", 1)[0].strip()  # `main [extra]`: extras mean nothing here
        if not equals or not colon or not name.strip() or not module.strip() or not function:
            raise SetupFileError(f"{where}: {spec.strip()!r} is not a console script (`name = package.module:function`)")
        return cls(name.strip(), module.strip(), function)

    def __repr__(self) -> str:
        return f"EntryPoint({self.name} = {self.module}:{self.function})"


def console_scripts(folder: Path) -> dict[str, EntryPoint]:
    """The console scripts of the package in ``folder``, by name (from setup.cfg, then setup.py)."""
    scripts: dict[str, EntryPoint] = {}
    cfg = folder / "setup.cfg"
    if cfg.is_file():
        scripts.update(_from_cfg(cfg))
    setup_py = folder / "setup.py"
    if setup_py.is_file():
        scripts.update(_from_setup_py(setup_py))
    return scripts


def _from_cfg(path: Path) -> dict[str, EntryPoint]:
    parser = configparser.ConfigParser(interpolation=None)
    try:
        parser.read(path, encoding="utf-8")
    except (configparser.Error, UnicodeDecodeError) as error:
        raise SetupFileError(f"{path}: {error}".splitlines()[0]) from None
    text = parser.get("options.entry_points", "console_scripts", fallback="")
    return _scripts([line for line in text.splitlines() if line.strip()], str(path))


def _from_setup_py(path: Path) -> dict[str, EntryPoint]:
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    except (SyntaxError, UnicodeDecodeError, OSError) as error:
        raise SetupFileError(f"{path}: cannot read it as Python ({error})".splitlines()[0]) from None
    names = _string_assignments(tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _called_name(node.func) == "setup":
            for keyword in node.keywords:
                if keyword.arg == "entry_points":
                    value = _literal(keyword.value, names, path)
                    return _entry_points(value, path)
    return {}


def _entry_points(value: Any, path: Path) -> dict[str, EntryPoint]:
    if isinstance(value, str):  # setuptools also takes the ini text
        parser = configparser.ConfigParser(interpolation=None)
        parser.read_string(value)
        lines = parser.get("console_scripts", "", fallback="")
        return _scripts([line for line in lines.splitlines() if line.strip()], str(path))
    if not isinstance(value, dict):
        raise SetupFileError(f"{path}: entry_points is not a dict of lists")
    scripts = value.get("console_scripts", [])
    if isinstance(scripts, str):
        scripts = [scripts]
    if not isinstance(scripts, list | tuple) or not all(isinstance(s, str) for s in scripts):
        raise SetupFileError(f"{path}: console_scripts is not a list of 'name = module:function' strings")
    return _scripts(list(scripts), str(path))


def _scripts(specs: list[str], where: str) -> dict[str, EntryPoint]:
    points = [EntryPoint.parse(spec, where) for spec in specs]
    return {point.name: point for point in points}


def _called_name(func: ast.expr) -> str:
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute):
        return func.attr
    return ""


def _string_assignments(tree: ast.Module) -> dict[str, str]:
    """Module-level ``name = "text"`` (and ``name = other + "text"``): what the call may use."""
    names: dict[str, str] = {}
    for statement in tree.body:
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1:
            target = statement.targets[0]
            if isinstance(target, ast.Name):
                try:
                    value = _literal(statement.value, names, None)
                except SetupFileError:
                    continue
                if isinstance(value, str):
                    names[target.id] = value
    return names


def _literal(node: ast.expr, names: dict[str, str], path: Path | None) -> Any:
    """The value of a literal expression, with the module's string variables; SetupFileError else."""
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name) and node.id in names:
        return names[node.id]
    if isinstance(node, ast.Dict):
        return {
            _literal(key, names, path): _literal(value, names, path)
            for key, value in zip(node.keys, node.values, strict=True)
            if key is not None
        }
    if isinstance(node, ast.List | ast.Tuple):
        return [_literal(item, names, path) for item in node.elts]
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _literal(node.left, names, path), _literal(node.right, names, path)
        if isinstance(left, str) and isinstance(right, str):
            return left + right
    if isinstance(node, ast.JoinedStr):
        parts = []
        for piece in node.values:
            if isinstance(piece, ast.FormattedValue):
                parts.append(str(_literal(piece.value, names, path)))
            else:
                parts.append(str(_literal(piece, names, path)))
        return "".join(parts)
    where = f"{path}:{node.lineno}" if path is not None else "setup.py"
    raise SetupFileError(
        f"{where}: entry_points must be written with literals (and simple string variables) "
        "for Skydeck to read it without running setup.py"
    )
