"""Imports run downward only: the lower layers never load the ones built on them.

shared_models (messages, names, errors) <- services.runtime (the SDK) <- services.access (tokens,
the fences) <- services.core and the nodes <- services.protocols (adapters over the core) <-
services.launch <- services.classroom (`skydeck class`) <- services.cli. A module
that imported upward would tie a layer to the one above it (the launcher to the CLI, the app to
the node it is part of, the core to a protocol). The table of endpoints is read by the launcher
and the CLI without loading a protocol or the core.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.timeout(60)

# module imported -> packages or modules it must not load
LAYERS = {
    "shared_models.catalogue": ("services", "sim_server"),
    "services.runtime": ("services.core", "services.launch", "services.cli", "services.ros"),
    "services.runtime.app": ("services.runtime.node",),
    "services.access": ("services.core", "services.protocols", "services.launch", "services.cli"),
    "services.core.app": ("services.protocols", "services.launch", "services.cli"),
    "services.core.server": ("services.protocols", "services.launch", "services.cli"),
    "services.protocols": ("services.core", "services.protocols.rosbridge", "services.protocols.foxglove"),
    "services.protocols.core_process": ("services.launch", "services.cli"),
    "services.protocols.rosbridge": ("services.protocols.foxglove", "services.launch", "services.cli"),
    "services.protocols.foxglove": ("services.protocols.rosbridge", "services.launch", "services.cli"),
    "services.launch.supervisor": ("services.cli",),
    "services.classroom": ("services.cli",),
    "services.core.classroom": ("services.protocols", "services.launch", "services.cli", "services.classroom"),
    "services.launch.plan": ("services.cli", "services.core", "services.protocols.rosbridge", "services.protocols.foxglove"),
    "sim_server.node": ("services.cli", "services.launch", "services.core", "sim_server.drone", "sim_server.robot"),
    "sim_server.drone.node": ("services.cli", "services.launch", "services.core", "sim_server.robot"),
    "sim_server.robot.node": ("services.cli", "services.launch", "services.core", "sim_server.drone"),
    "sim_server.world_node": ("sim_server.drone", "sim_server.robot", "sim_server.worlds"),
}


@pytest.mark.parametrize("module", list(LAYERS))
def test_a_layer_never_loads_the_layers_above_it(module: str) -> None:
    forbidden = LAYERS[module]
    code = (
        f"import importlib, sys; importlib.import_module({module!r}); "
        f"print(','.join(sorted(m for m in sys.modules for f in {forbidden!r} if m == f or m.startswith(f + '.'))))"
    )
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=50)
    assert loaded.stdout.strip() == "", f"importing {module} loads {loaded.stdout.strip()}"


# -- no import cycles ----------------------------------------------------------------------------

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("services", "shared_models", "sim_server", "benchmarks")
def _modules() -> dict[str, Path]:
    found: dict[str, Path] = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if "node_modules" in path.parts:
                continue
            parts = path.relative_to(ROOT).with_suffix("").parts
            found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


def _imports(module: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Every module of ours ``module`` imports: at the top, in functions, under TYPE_CHECKING."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    targets: list[str] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*up, base] if base else up)
            targets += [base, *(f"{base}.{alias.name}" for alias in node.names)]
    found = set()
    for target in targets:
        while target and target not in modules:  # a name inside a module: the module
            target = target.rpartition(".")[0]
        if target and target != module:
            found.add(target)
    return found


def _cycles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """The strongly connected groups of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups: list[frozenset[str]] = []

    def visit(start: str) -> None:
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, edges = work[-1]
            for target in edges:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(graph[target]))))
                    break
                if target in on_stack:
                    low[node] = min(low[node], index[target])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    group = set()
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        group.add(member)
                        if member == node:
                            break
                    if len(group) > 1:
                        groups.append(frozenset(group))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    return groups


def test_no_import_cycles_counting_type_only_and_function_level_imports() -> None:
    """A cycle ties modules into one piece (which to read first?); a type-only import counts too
    (split the types out), and a function-level one only hides it."""
    modules = _modules()
    graph = {module: _imports(module, path, modules) for module, path in modules.items()}
    cycles = [sorted(cycle) for cycle in _cycles(graph)]
    assert not cycles, f"import cycles: {cycles}"


def test_the_cycle_finder_finds_a_cycle_and_only_cycles() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert _cycles(graph) == [frozenset({"a", "b", "c"})]
