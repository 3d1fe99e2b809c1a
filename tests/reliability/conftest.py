"""Running systems for the reliability tests.

- ``launch`` (from tests/e2e): a real `skydeck launch` per test, for killing processes.
- ``workshop``: one `skydeck launch` of the whole workshop system shared by the session, for the
  bad-input matrix and the fuzzer, which only need it to keep answering.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, field

import httpx
import pytest

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
        nodes = _registered(core_url, {"/sim", "/perception", "/control", "/ai"}, timeout_s=10)
        yield Workshop(core_url, nodes, process.lines)
    finally:
        # Whatever the tests sent, the system stops cleanly and no process printed a traceback.
        stop_launch(process)


def _registered(core_url: str, names: set[str], timeout_s: float) -> dict[str, str]:
    """Node name -> URL once every one of ``names`` is registered; fails after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while True:
        nodes = {n["name"]: n["url"] for n in httpx.get(core_url + "/api/graph", timeout=5).json()["nodes"]}
        if names <= nodes.keys():
            return nodes
        if time.monotonic() > deadline:
            raise AssertionError(f"not registered after {timeout_s:g} s: {sorted(names - nodes.keys())}")
        time.sleep(0.1)
