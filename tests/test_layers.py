"""Imports run downward only: the lower layers never load the ones built on them.

shared_models (messages, names, errors) <- services.runtime (the SDK) <- services.access (tokens,
the fences) <- services.core and the nodes <- services.protocols (adapters over the core) <-
services.launch <- services.cli. A module
that imported upward would tie a layer to the one above it (the launcher to the CLI, the app to
the node it is part of, the core to a protocol). The table of endpoints is read by the launcher
and the CLI without loading a protocol or the core.
"""

from __future__ import annotations

import subprocess
import sys

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
