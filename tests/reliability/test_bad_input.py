"""Bad input wherever a byte enters the running workshop system: every service (from /api/graph)
and every writable topic (one a node subscribes to), on the node itself and through the core's
gateway. Each bad body or frame gets its 4xx or close code with a reason, and the node keeps
serving. Names with odd characters are refused with a message that shows the bad part.
"""

from __future__ import annotations

from typing import Any
from urllib.parse import quote

import httpx
import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from services.runtime.edge.links import stream_url
from services.runtime.service_groups import SYSTEM_NODES
from services.runtime.wire import MAX_MESSAGE_BYTES
from tests.bad_frames import OversizedFrame, bad_payloads, close_of
from tests.reliability.conftest import Workshop

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(300)]  # hang guards; serial requests on a loaded machine

OVERSIZED = MAX_MESSAGE_BYTES + 1


def _default(workshop: Workshop, type_name: str, part: str | None = None) -> dict[str, Any]:
    reply = httpx.get(f"{workshop.core_url}/api/interfaces/{type_name}", timeout=5).json()
    return reply["default"][part] if part else reply["default"]  # type: ignore[no-any-return]


def test_every_service_refuses_bad_bodies_and_keeps_serving(workshop: Workshop) -> None:
    services = workshop.graph()["services"]
    assert {s["name"] for s in services} >= {"/control/fly", "/control/take_off", "/simulator/reset", "/ai/start"}
    checked = 0
    for service in services:
        node = service["node"]
        cases = {name: (body, "application/json", 422) for name, body in
                 bad_payloads(_default(workshop, service["type"], "request")).items()}
        cases["oversized"] = (b"{" + b" " * (OVERSIZED - 2) + b"}", "application/json", 413)
        cases["binary"] = (bytes(range(256)), "application/octet-stream", 422)
        for base in (workshop.core_url, workshop.node_urls[node]):
            for case, (body, content_type, expected) in cases.items():
                reply = httpx.post(base + service["name"], content=body, headers={"content-type": content_type}, timeout=10)
                where = f"{case} to {service['name']} via {base}"
                assert reply.status_code == expected, (where, reply.status_code, reply.text[:300])
                assert reply.json()["detail"], where  # a reason: FastAPI's list, or a sentence
                checked += 1
            assert workshop.node_serves(node), node
    print(f"bad bodies: {checked} cases on {len(services)} services")
    assert checked >= len(services) * 2 * 6


def test_every_writable_topic_refuses_bad_frames_and_keeps_serving(workshop: Workshop) -> None:
    graph = workshop.graph()
    # The workshop's nodes take frames on topics they subscribe to; the core's own nodes (the core
    # node reading for its clients, the guests it answers for rosbridge clients: rosapi,
    # tf2_web_republisher) publish only what their clients publish, so they are not among them.
    nodes = {name: url for name, url in workshop.node_urls.items() if name not in SYSTEM_NODES}
    writable = [t for t in graph["topics"] if any(s in nodes for s in t["subscribers"])]
    assert {t["name"] for t in writable} >= {"/drone/setpoint", "/drone/cmd_vel", "/drone/pose", "/perception/boxes"}
    checked = 0
    for topic in writable:
        cases: dict[str, tuple[str | bytes | OversizedFrame, int]] = {
            name: (body.decode(), 1007) for name, body in bad_payloads(_default(workshop, topic["type"])).items()
        }
        cases["oversized"] = (OversizedFrame(OVERSIZED), 1009)
        cases["binary"] = (bytes(range(256)), 1003)
        subscribers = [s for s in topic["subscribers"] if s in nodes]
        for base in [workshop.core_url, *(nodes[s] for s in subscribers)]:
            for case, (payload, expected) in cases.items():
                code, reason = close_of(stream_url(base, topic["name"]), payload)
                where = f"{case} on {topic['name']} via {base}"
                assert code == expected, (where, code, reason)
                if expected != 1009:  # the server's frame limit closes before the frame is read
                    assert reason, where
                checked += 1
        for subscriber in subscribers:
            assert workshop.node_serves(subscriber), subscriber
    print(f"bad frames: {checked} cases on {len(writable)} writable topics")
    assert checked >= len(writable) * 2 * 8


@pytest.mark.parametrize(
    ("name", "bad_part"),
    [("/drone/po se", "' '"), ("/a//b", "empty token"), ("/ünïcode", "'ü'"), ("/x?y", "'?'"), ("/drone/pose/", "trailing")],
)
def test_odd_names_are_refused_with_the_bad_part_shown(workshop: Workshop, name: str, bad_part: str) -> None:
    path = quote(name)
    for method in ("GET", "POST"):
        reply = httpx.request(method, workshop.core_url + path, timeout=5)
        assert reply.status_code == 404, (method, name, reply.text)
        assert bad_part in reply.json()["detail"] and "invalid name" in reply.json()["detail"], reply.text
    ws_url = workshop.core_url.replace("http://", "ws://") + path
    with connect(ws_url, open_timeout=5) as websocket, pytest.raises(ConnectionClosed) as closed:
        websocket.recv(timeout=5)
    assert closed.value.rcvd is not None
    assert closed.value.rcvd.code == 1008 and bad_part in closed.value.rcvd.reason
