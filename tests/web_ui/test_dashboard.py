"""The dashboard against the real system (core, sim, control), driven in Chromium.

The tests of this module share one running system and run in file order: the drone first
drives by teleop, is reset, takes off, then flies where the map is clicked. Waits are on the
dashboard's own state (``window.skydeck``), never fixed sleeps.
"""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from urllib.parse import urlsplit

import pytest

from tests.web_ui.system import System
from tests.web_ui.view3d_page import open_3d
from tests.web_ui.world_names import read_topics, untyped_topics, world_topics

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


def call_service(system: System, name: str, body: dict[str, object] | None = None) -> dict[str, object]:
    """POST a service through the core's gateway, as the CLI would."""
    request = urllib.request.Request(
        system.url + name,
        data=json.dumps(body or {}).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=10) as reply:
        return json.loads(reply.read())  # type: ignore[no-any-return]


def get_latest(system: System, topic: str) -> dict[str, object] | None:
    try:
        with urllib.request.urlopen(system.url + topic, timeout=5) as reply:
            return json.loads(reply.read())  # type: ignore[no-any-return]
    except urllib.error.HTTPError:
        return None


def pose(page) -> dict[str, float]:  # type: ignore[no-untyped-def]
    return page.evaluate("window.skydeck.pose")  # type: ignore[no-any-return]


def test_page_loads_without_errors_and_talks_only_to_the_core(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    page.wait_for_function("window.skydeck.mapFrames > 10 && window.skydeck.coreReachable", timeout=10_000)
    # Every socket is open but those of names nobody publishes here (no perception, no AI).
    page.wait_for_function("window.skydeck.sockets().every(s => s.state === 'open' || s.state === 'waiting')", timeout=10_000)
    waiting = page.evaluate("window.skydeck.sockets().filter(s => s.state === 'waiting').map(s => s.topic)")
    assert sorted(waiting) == ["/ai/status", "/perception/boxes"]
    assert page.title() == "Skydeck"
    assert recorder.errors == []
    core = urlsplit(system.url).netloc
    outside = [u for u in recorder.urls if not u.startswith("data:") and urlsplit(u).netloc != core]
    assert outside == [], f"requests leaving the core: {outside}"
    assert any(u.startswith(f"ws://{core}/drone/pose") for u in recorder.urls)
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'ok'", timeout=5_000)
    assert page.locator("#status-banner").is_hidden()


def test_lists_topics_services_and_nodes(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    topics = page.locator("#topic-list")
    for name in ("/drone/pose", "/drone/setpoint", "/simulator/boxes", "/drone/cmd_vel"):
        topics.locator(f'tr[data-topic="{name}"]').wait_for(timeout=10_000)
    row = topics.locator('tr[data-topic="/drone/pose"]')
    assert row.get_attribute("data-type") == "geometry_msgs/msg/PoseStamped"
    assert "PoseStamped" in row.inner_text()
    page.wait_for_function(
        "[...document.querySelectorAll('#topic-list tr[data-topic=\"/drone/pose\"] td.num')]"
        ".some(td => parseFloat(td.textContent) > 10)",
        timeout=10_000,
    )
    for name in ("/control/take_off", "/control/fly", "/simulator/reset"):
        page.locator(f'#service-list tr[data-service="{name}"]').wait_for(timeout=10_000)
    for name in ("/sim", "/control"):
        page.locator(f'#node-list li[data-node="{name}"]').wait_for(timeout=10_000)
    page.click("[data-tab=graph]")
    page.locator('#graph-diagram g[data-name="/drone/pose"]').wait_for(timeout=10_000)


def test_a_bridges_ros2_nodes_are_listed_and_drawn_as_ros2(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    from services.runtime.protocol import Entity, ForeignNode
    from tests.web_ui.threaded_node import ThreadedNode

    page, _ = dashboard
    bridge = ThreadedNode("fake_ros2_bridge", system.url)  # says what a ROS 2 bridge says
    talker = ForeignNode(name="/talker", system="ros2", publications=[Entity(name="/chatter", type="std_msgs/msg/String")])
    try:
        bridge._loop.call_soon_threadsafe(bridge.node.set_foreign_participants, [talker])
        item = page.locator('#node-list li[data-node="/talker"]')
        item.wait_for(timeout=10_000)
        assert "ROS 2 node, via /fake_ros2_bridge" in item.inner_text()
        page.click("[data-tab=graph]")
        page.locator('#graph-diagram g.vertex.node.ros2[data-name="/talker"]').wait_for(timeout=10_000)
        assert page.locator('#graph-diagram g.vertex.node.ros2[data-name="/sim"]').count() == 0
    finally:
        bridge.close()


def test_teleop_drives_the_drone_only_when_on(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    start = pose(page)
    assert start["z"] < 0.3, "the drone should start on the ground"
    # Off by default: keys do nothing.
    page.locator("#map").hover()
    page.keyboard.down("r")
    page.keyboard.up("r")
    assert page.evaluate("window.skydeck.teleop.sent") == 0
    assert page.get_attribute("#teleop-toggle", "aria-pressed") == "false"

    page.click("#teleop-toggle")
    assert page.get_attribute("#teleop-toggle", "aria-pressed") == "true"
    page.wait_for_function(
        "window.skydeck.sockets().some(s => s.topic === '/drone/cmd_vel' && s.state === 'open')", timeout=10_000
    )
    # Typing in a form field never drives the drone.
    page.click("#log-filter")
    page.keyboard.type("rrr")
    assert page.evaluate("window.skydeck.teleop.sent") == 0
    page.fill("#log-filter", "")
    page.locator("#map").hover()
    page.evaluate("document.activeElement.blur()")

    page.keyboard.down("r")
    page.wait_for_function("window.skydeck.pose.z > 1.0", timeout=20_000)
    page.keyboard.up("r")
    x0 = pose(page)["x"]
    page.keyboard.down("ArrowRight")
    page.wait_for_function("x0 => window.skydeck.pose.x > x0 + 1.0", arg=x0, timeout=20_000)
    page.keyboard.up("ArrowRight")
    teleop = page.evaluate("window.skydeck.teleop")
    assert teleop["held"] == []
    assert teleop["twist"]["linear"] == {"x": 0, "y": 0, "z": 0}
    assert teleop["sent"] > 5

    page.click("#teleop-toggle")
    assert page.get_attribute("#teleop-toggle", "aria-pressed") == "false"
    # Back on the ground at the start for the next tests.
    page.click("#reset")
    page.wait_for_function(
        "() => { const r = window.skydeck.lastCommand; return r && r.service === '/simulator/reset' && r.kind !== 'pending'; }",
        timeout=10_000,
    )
    assert page.get_attribute("#command-result", "data-kind") == "success"
    page.wait_for_function(
        "() => { const p = window.skydeck.pose; return p.z < 0.3 && Math.hypot(p.x, p.y) < 0.5; }", timeout=20_000
    )


def test_take_off_button_makes_the_drone_climb(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    page.click("#takeoff")
    page.wait_for_function("window.skydeck.pose.z > 1.0", timeout=30_000)
    # The drone can climb before the answer reaches the page: wait for the answer too.
    page.wait_for_function(
        "() => { const r = window.skydeck.lastCommand; return r && r.service === '/control/take_off' && r.kind !== 'pending'; }",
        timeout=10_000,
    )
    assert page.get_attribute("#command-result", "data-kind") == "success"
    assert page.get_attribute("#command-result", "data-service") == "/control/take_off"
    page.wait_for_function("window.skydeck.pose.z > 2.5", timeout=30_000)
    # Control logged it on /rosout: the console shows it, and filters it by level and node.
    page.wait_for_function(
        "window.skydeck.log.some(e => e.name === '/control' && e.level === 20)", timeout=10_000
    )
    page.locator("#log .log-entry[data-level=INFO]").first.wait_for(timeout=5_000)
    page.select_option("#log-level", "30")
    assert page.locator("#log .log-entry[data-level=INFO]").count() == 0
    page.select_option("#log-level", "10")
    page.select_option("#log-node", "/control")
    names = page.locator("#log .log-node").all_inner_texts()
    assert names and set(names) == {"[/control]"}


def test_refusals_and_http_errors_are_told_apart(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    if pose(page)["z"] < 1.0:
        call_service(system, "/control/take_off")
        page.wait_for_function("window.skydeck.pose.z > 1.0", timeout=30_000)
    page.click("#takeoff")  # already flying: control refuses
    page.wait_for_function("document.querySelector('#command-result').dataset.kind === 'refused'", timeout=10_000)
    assert "refused" in page.inner_text("#command-result")
    page.click("#mission-start")  # no AI node in this system: the gateway answers 404
    page.wait_for_function(
        "() => { const r = window.skydeck.lastCommand; return r.service === '/ai/start' && r.kind === 'error'; }",
        timeout=10_000,
    )
    assert "404" in page.inner_text("#command-result")


def test_added_topic_layer_shows_the_seeds_point(dashboard, my_point) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    page.click("[data-tab=layers]")
    page.wait_for_function(
        "document.querySelector('#add-topic-select option[value=\"/my_point\"]') !== null", timeout=10_000
    )
    page.select_option("#add-topic-select", "/my_point")
    page.click("#add-topic")
    page.wait_for_function(
        "window.skydeck.layers().some(l => l.topic === '/my_point' && l.count === 1)", timeout=10_000
    )
    (layer,) = [entry for entry in page.evaluate("window.skydeck.layers()") if entry["topic"] == "/my_point"]
    assert layer["type"] == "geometry_msgs/msg/PointStamped"
    assert layer["frame"] == "odom"
    assert layer["points"] == [{"x": 1, "y": 2, "z": 0}]
    page.locator('#layer-list li[data-topic="/my_point"]').wait_for()
    assert "1 point" in page.inner_text('#layer-list li[data-topic="/my_point"]')
    # The layer survives a reload (kept in localStorage) and can be removed.
    page.reload()
    page.wait_for_function(
        "window.skydeck && window.skydeck.layers().some(l => l.topic === '/my_point' && l.count === 1)",
        timeout=10_000,
    )
    page.click("[data-tab=layers]")
    page.click('#layer-list li[data-topic="/my_point"] [data-action=remove]')
    page.wait_for_function("window.skydeck.layers().length === 0", timeout=5_000)


def test_click_on_map_flies_there(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    if pose(page)["z"] < 1.0:
        call_service(system, "/control/take_off")
        page.wait_for_function("window.skydeck.pose.z > 2.5", timeout=30_000)
    target = {"x": 6.0, "y": -5.0}
    point = page.evaluate("t => window.skydeck.worldToClient(t.x, t.y)", target)
    page.mouse.click(point["x"], point["y"])
    page.wait_for_function(
        "() => { const r = window.skydeck.lastCommand; return r && r.service === '/control/fly' && r.kind !== 'pending'; }",
        timeout=10_000,
    )
    assert page.get_attribute("#command-result", "data-kind") == "success", page.inner_text("#command-result")
    sent = page.evaluate("window.skydeck.lastCommand.request")
    assert abs(sent["x"] - target["x"]) < 0.2 and abs(sent["y"] - target["y"]) < 0.2
    page.wait_for_function(
        "t => { const c = window.skydeck.controlState; return c && Math.hypot(c.setpoint.x - t.x, c.setpoint.y - t.y) < 0.3; }",
        arg=target,
        timeout=10_000,
    )
    start = pose(page)
    start_distance = ((start["x"] - target["x"]) ** 2 + (start["y"] - target["y"]) ** 2) ** 0.5
    page.wait_for_function(
        "([t, d]) => { const p = window.skydeck.pose; return Math.hypot(p.x - t.x, p.y - t.y) < Math.min(d / 2, 3); }",
        arg=[target, start_distance],
        timeout=30_000,
    )
    page.wait_for_function(
        "t => { const p = window.skydeck.pose; return Math.hypot(p.x - t.x, p.y - t.y) < 1.0; }",
        arg=target,
        timeout=30_000,
    )


def test_inspector_echoes_pauses_and_publishes(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    page.click('#topic-list tr[data-topic="/drone/pose"]')
    page.wait_for_function("document.querySelector('#inspect-echo').textContent.includes('position')", timeout=10_000)
    assert "geometry_msgs/msg/PoseStamped" in page.inner_text("#inspect-info")
    page.click("#inspect-pause")
    frozen = page.inner_text("#inspect-echo")
    received = page.evaluate("() => document.querySelector('#inspect-stats').textContent")
    page.wait_for_function(
        "before => document.querySelector('#inspect-stats').textContent !== before", arg=received, timeout=5_000
    )
    assert page.inner_text("#inspect-echo") == frozen
    page.click("#inspect-pause")

    # A topic nobody publishes yet: choose its type, fill the generated form, publish.
    page.fill("#inspect-name", "/ui_test_point")
    page.press("#inspect-name", "Enter")
    page.wait_for_function(
        "document.querySelector('#inspect-type option[value=\"geometry_msgs/msg/PointStamped\"]') !== null",
        timeout=10_000,
    )
    page.select_option("#inspect-type", "geometry_msgs/msg/PointStamped")
    page.locator('[data-field="point.x"]').wait_for(timeout=10_000)
    page.fill('[data-field="point.x"]', "3.5")
    page.fill('[data-field="header.frame_id"]', "odom")
    page.wait_for_function(
        # the echo socket and the publishing socket (the core sends no socket its own frames)
        "(() => { const s = window.skydeck.sockets().filter(s => s.topic === '/ui_test_point');"
        " return s.length === 2 && s.every(s => s.state === 'open'); })()",
        timeout=10_000,
    )
    page.click("#inspect-send")
    page.wait_for_function("document.querySelector('#inspect-echo').textContent.includes('3.5')", timeout=10_000)
    latest = get_latest(system, "/ui_test_point")
    assert latest is not None and latest["point"]["x"] == 3.5  # type: ignore[index]

    # A frame that is not of the type: the core closes the socket (1007) and the reason is shown.
    page.click("#inspect-json-details summary")
    page.fill("#inspect-json", '{"point": {"x": "not a number"}}')
    page.click("#inspect-send")
    page.wait_for_function(
        "document.querySelector('#inspect-result').textContent.includes('1007')", timeout=10_000
    )
    assert page.get_attribute("#inspect-result", "data-kind") == "error"


def test_the_page_reads_only_what_is_published_and_makes_no_ghost_topic(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    # This system runs no perception and no AI: their names (the drone world's, from its
    # description) are waited for, never read, so no topic appears without a publisher.
    page, recorder = dashboard
    open_3d(page)
    page.wait_for_function("window.skydeck.sockets().some(s => s.topic === '/perception/boxes' && s.state === 'waiting')", timeout=10_000)
    read = read_topics(recorder.urls, system.url)
    assert {"/drone/pose", "/simulator/boxes", "/simulator/world"} <= read, read
    assert read & {"/perception/boxes", "/ai/status", "/tf", "/tf_static"} == set(), read
    assert read <= world_topics(system.url, "drone") | {"/simulator/world", "/rosout"}
    assert untyped_topics(system.url) == []


def test_banner_and_reconnection_when_the_core_or_the_simulator_goes_away(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    # Last in the module: it stops the core, then the simulator.
    page, _ = dashboard
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'ok'", timeout=5_000)
    system.processes["core"].stop()
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'error'", timeout=15_000)
    assert "Core unreachable" in page.inner_text("#status-banner")
    assert page.get_attribute("#core-status", "data-state") == "error"

    # The core comes back on the same port: nodes re-register, every socket reconnects by itself.
    system.start("core", ["core"], system.base_port)
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'ok'", timeout=30_000)
    before = page.evaluate("window.skydeck.sockets().find(s => s.topic === '/drone/pose').messages")
    page.wait_for_function(
        "n => window.skydeck.sockets().find(s => s.topic === '/drone/pose').messages > n + 30", arg=before, timeout=15_000
    )

    system.processes["sim"].stop()
    page.wait_for_function("document.querySelector('#status-banner').dataset.state === 'warn'", timeout=15_000)
    assert "Simulator not" in page.inner_text("#status-banner")

