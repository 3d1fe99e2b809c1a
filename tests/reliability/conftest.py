"""Running systems for the reliability tests.

- ``launch`` (from tests/e2e): a real `skydeck launch` per test, for killing processes.
- ``workshop``: one `skydeck launch` of the whole workshop system shared by the session, for the
  bad-input matrix and the fuzzer, which only need it to keep answering.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

import httpx
import pytest

from tests.conftest import registered_nodes
from tests.e2e.conftest import LaunchedSystem, launch, start_launch, stop_launch

__all__ = ["LaunchedSystem", "Workshop", "launch", "workshop"]


@dataclass
class Workshop:
    """A launched workshop system: the core's URL and each node's own URL (from /api/graph)."""

    core_url: str
    node_urls: dict[str, str]
    lines: list[str] = field(default_factory=list)

    def graph(self) -> dict:
        return httpx.get(self.core_url + "/api/graph", timeout=5).json()  # type: ignore[no-any-return]

    def node_serves(self, node: str) -> bool:
        """The node answers /health on its own port and is still registered with the core."""
        health = httpx.get(self.node_urls[node] + "/health", timeout=5)
        return health.status_code == 200 and node in {n["name"] for n in self.graph()["nodes"]}


@pytest.fixture(scope="session")
def workshop(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Workshop]:
    process, core_url = start_launch(
        "--seed", "1", state_dir=tmp_path_factory.mktemp("state"), unset=("SKYDECK_TOKEN",)
    )
    try:
        process.wait_for_line("[launch] all", timeout_s=60)
        nodes = registered_nodes(core_url, {"/sim", "/perception", "/control", "/ai"}, timeout_s=10)
        yield Workshop(core_url, nodes, process.lines)
    finally:
        # Whatever the tests sent, the system stops cleanly and no process printed a traceback.
        stop_launch(process)
