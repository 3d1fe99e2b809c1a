"""The simulator's house: a floor that never imports a world, worlds that import only the
floor, no import cycle (type-only imports count), no module over 500 lines, and a table, an
entry and descriptions that load no world and no PyBullet."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.timeout(60)

PACKAGE = Path(__file__).resolve().parents[2] / "sim_server"
WORLD_PACKAGES = ("sim_server.drone", "sim_server.robot", "sim_server.soccer")
# A world built on another imports that world's package too; its description says which.
EXTENDS = {"sim_server.soccer": "sim_server.robot"}
ROOF = ("sim_server.worlds", "sim_server.node")  # the table and the entry: above every world


def _modules() -> dict[str, Path]:
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


MODULES = _modules()


def _imports(path: Path) -> set[str]:
    """The sim_server modules ``path`` imports, anywhere in it (under TYPE_CHECKING too)."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names |= {node.module} | {f"{node.module}.{alias.name}" for alias in node.names}
    found = set()
    for name in names:
        while name and name not in MODULES:
            name = name.rpartition(".")[0]
        if name.startswith("sim_server"):
            found.add(name)
    return found


def _package_of(module: str) -> str:
    for package in WORLD_PACKAGES:
        if module == package or module.startswith(package + "."):
            return package
    return "roof" if module in ROOF else "floor"


def test_the_floor_imports_no_world_and_a_world_only_the_floor() -> None:
    wrong = []
    for module, path in MODULES.items():
        home = _package_of(module)
        for imported in _imports(path) - {module}:
            where = _package_of(imported)
            if home == "floor" and where != "floor":
                wrong.append(f"floor {module} imports {imported}")
            elif home in WORLD_PACKAGES and where not in ("floor", home, EXTENDS.get(home)):
                wrong.append(f"world {module} imports {imported}")
    assert wrong == []


def test_a_world_built_on_another_says_so() -> None:
    from sim_server.worlds import WORLDS

    said = {f"sim_server.{name}": f"sim_server.{entry.describe().extends}" for name, entry in WORLDS.items() if entry.describe().extends}
    assert said == EXTENDS


def test_no_import_cycle() -> None:
    graph = {module: _imports(path) - {module} for module, path in MODULES.items()}
    # A package's __init__ is not a step on the way (importing a.b runs a first, but a does
    # not import a.b here: the worlds' __init__ load their names lazily).
    cycles = []

    def visit(module: str, trail: list[str]) -> None:
        for imported in sorted(graph.get(module, ())):
            if imported in trail:
                cycles.append(trail[trail.index(imported) :] + [imported])
            elif imported not in done:
                visit(imported, [*trail, imported])
        done.add(module)

    done: set[str] = set()
    for module in sorted(graph):
        if module not in done:
            visit(module, [module])
    assert cycles == []


def test_no_module_over_500_lines() -> None:
    long = {module: n for module, path in MODULES.items() if (n := len(path.read_text().splitlines())) > 500}
    assert long == {}


@pytest.mark.parametrize(
    "module",
    [
        "sim_server.worlds",
        "sim_server.node",
        "sim_server.settings",
        "sim_server.drone.limits",
        "sim_server.drone.settings",
        "sim_server.drone.description",
        "sim_server.robot.limits",
        "sim_server.robot.settings",
        "sim_server.robot.description",
        "sim_server.soccer.limits",
        "sim_server.soccer.settings",
        "sim_server.soccer.description",
    ],
)
def test_the_table_the_entry_and_what_clients_read_load_no_physics(module: str) -> None:
    code = (
        f"import importlib, sys; importlib.import_module({module!r}); "
        "from sim_server.worlds import worlds_config, world_options; worlds_config(); world_options(); "
        "print(','.join(sorted(m for m in sys.modules if m == 'pybullet' or m.endswith(('.node', '.world', '.world_node'))"
        " and m.startswith('sim_server'))))"
    )
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=50)
    loaded_names = [name for name in loaded.stdout.strip().split(",") if name and name != "sim_server.node"]
    assert loaded_names == [], f"importing {module} loads {loaded_names}"
