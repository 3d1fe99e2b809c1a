"""The class page in Chromium (issue 35): the instructor's token shows the Class tab with every
student's robot in one 3D scene and a table (nodes, last message age, grade from the gradebook);
clicking a student shows their topics. A student's token shows no Class tab, and their dashboard
reads and lists only what the token may read (their robot, the shared names).

A class of its own: the core with the class's tokens and gradebook, the robot world with a robot
per student (alice, bob), both with the class's process token, as `skydeck class` starts them.
"""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from services.access import make_class_tokens, write_tokens
from tests.conftest import free_port_block
from tests.web_ui.conftest import Recorder
from tests.web_ui.system import System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(150)]

PROCESS_TOKEN = "the-class-processes-own-token"


@dataclass
class ClassSystem:
    system: System
    tokens: dict[str, str]
    gradebook: Path


@pytest.fixture(scope="module")
def classroom(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ClassSystem]:
    folder = tmp_path_factory.mktemp("class")
    tokens = make_class_tokens(["alice", "bob"])
    write_tokens(folder / "class-tokens.csv", tokens)
    gradebook = folder / "gradebook.json"
    base = free_port_block(5)
    running = System(base)
    env = {"SKYDECK_TOKEN": PROCESS_TOKEN}
    try:
        running.start(
            "core", ["core", "--class-tokens", str(folder / "class-tokens.csv"), "--class-gradebook", str(gradebook)],
            base, env=env,
        )  # fmt: skip
        running.start(
            "sim", ["run", "sim", "--world", "robot", "--speed", "1", "--seed", "1", "--obstacles", "2"], base + 1,
            env={**env, "SKYDECK_SIM_STUDENTS": "alice,bob"},
        )  # fmt: skip
        yield ClassSystem(running, tokens, gradebook)
    finally:
        running.stop()


@contextlib.contextmanager
def _page(browser: object, classroom: ClassSystem, who: str) -> Iterator[tuple[object, Recorder]]:
    """A fresh page on the class's dashboard at /#class, signed in with ``who``'s token."""
    context = browser.new_context(viewport={"width": 1440, "height": 900})  # type: ignore[attr-defined]
    context.add_init_script(f"sessionStorage.setItem('skydeck.token', {json.dumps(classroom.tokens[who])})")
    try:
        page = context.new_page()
        recorder = Recorder()
        recorder.attach(page)
        page.goto(classroom.system.url + "/#class")
        yield page, recorder
    finally:
        context.close()


def test_the_instructor_sees_every_robot_the_table_and_a_students_topics(classroom: ClassSystem, browser) -> None:  # type: ignore[no-untyped-def]
    classroom.gradebook.write_text(json.dumps({"assignment": "wall_follower", "students": {
        "alice": {"score": 0.9, "passed": True, "criteria": [{"name": "in_band", "passed": True, "figure": "92%", "verdict": "ok"}]},
        "bob": {"score": 0.2, "passed": False, "criteria": [{"name": "no_collisions", "passed": False, "figure": "3 bumps", "verdict": "bumped"}]},
    }}))  # fmt: skip
    with _page(browser, classroom, "instructor") as (page, recorder):
        page.wait_for_function(
            "(() => { const c = window.skydeck && window.skydeck.classPage; return c && c.shown && c.rows.length === 2"
            " && c.scene && c.scene.robots.length === 2 && c.scene.robots.every(r => r.name) && c.scene.roomParts > 0; })()",
            timeout=30_000,
        )
        assert page.is_visible("#class-tab") and page.get_attribute("#class-tab", "aria-selected") == "true"
        rows = page.locator("#class-table tbody tr")
        assert rows.count() == 2
        assert rows.nth(0).inner_text().split("\t")[0] == "alice" and "0.90 ✓" in rows.nth(0).inner_text()
        assert "0.20 ✗" in rows.nth(1).inner_text() and "none" in rows.nth(1).inner_text()  # bob runs no node
        assert page.inner_text("#class-assignment") == "assignment: wall_follower"
        scene = page.evaluate("window.skydeck.classPage.scene")
        assert [r["name"] for r in scene["robots"]] == ["alice", "bob"]
        assert scene["robots"][0]["x"] != scene["robots"][1]["x"] or scene["robots"][0]["y"] != scene["robots"][1]["y"]

        rows.nth(1).click()
        page.wait_for_function("window.skydeck.classPage.topics.includes('/bob/odom')", timeout=15_000)
        state = page.evaluate("window.skydeck.classPage")
        assert state["selected"] == "bob" and {"/bob/cmd_vel", "/bob/scan", "/bob/bump"} <= set(state["topics"])
        assert not [t for t in state["topics"] if not t.startswith("/bob/")]
        assert [r["name"] for r in state["scene"]["robots"] if r["selected"]] == ["bob"]
        assert "no_collisions" in page.inner_text("#class-detail")
        page.click("#class-detail button:text('/bob/odom')")  # a topic opens in the Inspector
        page.wait_for_function("document.getElementById('inspect-name').value === '/bob/odom'", timeout=10_000)
        assert recorder.errors == []
        host = classroom.system.url.split("//")[1]
        assert all(host in url or url.startswith(("data:", "blob:")) for url in recorder.urls), "no CDN: every file from the core"


def test_a_students_dashboard_reads_only_what_their_token_may(classroom: ClassSystem, browser) -> None:  # type: ignore[no-untyped-def]
    with _page(browser, classroom, "alice") as (page, recorder):
        page.wait_for_function(
            "window.skydeck && window.skydeck.access && window.skydeck.access.role === 'student'"
            " && window.skydeck.room.robots.length === 1 && window.skydeck.room.robots[0].odom !== null",
            timeout=30_000,
        )
        assert page.is_hidden("#class-tab")
        assert page.evaluate("window.skydeck.world.namespaces") == ["/alice", "/bob"]
        assert page.evaluate("window.skydeck.room.robots[0].namespace") == "/alice"
        topics = page.evaluate("window.skydeck.graph.topics.map(t => t.name)")
        assert "/alice/odom" in topics and "/clock" in topics
        assert not [t for t in topics if t.startswith("/bob/") or t == "/simulator/robots"]
        assert not [url for url in recorder.urls if "/bob/" in url or "/simulator/robots" in url]
        assert page.evaluate("window.skydeck.teleop.topic") == "/alice/cmd_vel"
        refused = page.evaluate("window.skydeck.sockets().filter(s => s.state === 'closed').map(s => s.topic)")
        assert refused == []  # nothing was opened only to be refused
        assert page.locator("#token-dialog[open]").count() == 0
        assert recorder.errors == []
