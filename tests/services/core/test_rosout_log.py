"""The core keeps the last lines of /rosout (ROS 1's rosout node) and serves them at
GET /api/rosout, so a console that opens late shows what was said before."""

from __future__ import annotations

import asyncio

import httpx

from services.core.rosout_log import BACKLOG_LINES
from services.runtime import Node


class Chatty(Node):
    def __init__(self, settings) -> None:  # type: ignore[no-untyped-def]
        super().__init__("chatty", settings=settings)


async def _backlog(core, limit: int | None = None) -> httpx.Response:  # type: ignore[no-untyped-def]
    query = "" if limit is None else f"?limit={limit}"
    async with httpx.AsyncClient() as http:
        return await http.get(f"{core.url}/api/rosout{query}", timeout=5)


async def _linked(core, node: Node) -> None:  # type: ignore[no-untyped-def]
    """Until the core reads the node's /rosout: a line said before its link is not kept (as
    ROS 1's rosout node misses what a node says before it connects)."""
    async with asyncio.timeout(10):
        while not any(line["name"] == node.get_name() for line in (await _backlog(core)).json()):
            node.get_logger().info("hello?")
            await asyncio.sleep(0.05)


async def test_the_core_reads_rosout_for_good_and_serves_the_last_lines_oldest_first(core, start_node) -> None:
    node = await start_node(Chatty)
    graph = core.registry.graph()
    assert "/skydeck_core" in next(t for t in graph["topics"] if t["name"] == "/rosout")["subscribers"]
    await _linked(core, node)
    for number in range(5):
        node.get_logger().info("line %d", number)
    node.get_logger().warning("the last one")

    async def kept() -> list[dict]:  # type: ignore[type-arg]
        return [line for line in (await _backlog(core)).json() if line["msg"] != "hello?"]

    lines: list[dict] = []  # type: ignore[type-arg]
    async with asyncio.timeout(10):
        while len(lines) < 6:
            await asyncio.sleep(0.05)
            lines = await kept()
    assert [line["msg"] for line in lines] == ["line 0", "line 1", "line 2", "line 3", "line 4", "the last one"]
    assert lines[-1]["level"] == 30 and lines[-1]["function"] == "test_the_core_reads_rosout_for_good_and_serves_the_last_lines_oldest_first"
    last_two = (await _backlog(core, 2)).json()
    assert [line["msg"] for line in last_two] == ["line 4", "the last one"]


async def test_a_bad_limit_is_a_422_naming_it(core) -> None:
    for limit in (0, BACKLOG_LINES + 1):
        reply = await _backlog(core, limit)
        assert reply.status_code == 422 and reply.json()["detail"][0]["loc"] == ["query", "limit"]
    assert (await _backlog(core)).json() == []  # nothing said yet


async def test_the_backlog_keeps_only_the_last_lines(core, start_node) -> None:
    node = await start_node(Chatty)
    await _linked(core, node)
    for number in range(BACKLOG_LINES + 20):
        node.get_logger().info("line %d", number)
    last = f"line {BACKLOG_LINES + 19}"
    lines: list[dict] = []  # type: ignore[type-arg]
    async with asyncio.timeout(10):
        while not lines or lines[-1]["msg"] != last:
            await asyncio.sleep(0.05)
            lines = (await _backlog(core, BACKLOG_LINES)).json()
    assert len(lines) == BACKLOG_LINES and lines[0]["msg"] == "line 20"
