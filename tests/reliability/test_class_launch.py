"""`skydeck class ROSTER` as an instructor runs it: one core fenced by the roster's tokens and the
robot world with a robot per student under /NAME; a student's program drives their robot only;
the class page's table (GET /api/class) is the instructor's, with each student's nodes, last
message age and grade from the gradebook (issue 35). Real processes, sockets and physics."""

from __future__ import annotations

import json
import math
import os
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import httpx
import pytest

from services.launch.background import BackgroundProcess
from services.runtime.ports import free_port_block
from tests.reliability.classroom import WALL_FOLLOWER

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(180)]

REPO = Path(__file__).resolve().parents[2]


def wait_until_sync(predicate: Callable[[], bool], timeout_s: float, what: str) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.1)  # polling a process over HTTP: there is no event to await


class Class:
    def __init__(self, folder: Path, url: str, tokens: dict[str, str]) -> None:
        self.folder, self.url, self.tokens = folder, url, tokens

    def get(self, path: str, who: str | None = "instructor") -> httpx.Response:
        headers = {"Authorization": f"Bearer {self.tokens[who]}"} if who else {}
        return httpx.get(self.url + path, headers=headers, timeout=10)


@pytest.fixture(scope="module")
def running(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    folder = tmp_path_factory.mktemp("class")
    (folder / "students.csv").write_text("name\nalice\nbob\n")
    # The default shared reads, written out: the class starts with its rules file as given.
    (folder / "rules.yaml").write_text("shared:\n  read: [/clock, /tf, /tf_static, /simulator/world, /simulator/obstacles]\n")
    base = free_port_block(1100)  # the core, the world, and the endpoints moved with the base port
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "class", str(folder / "students.csv"), "--base-port", str(base),
         "--seed", "7", "--gradebook", str(folder / "gradebook.json"), "--rules", str(folder / "rules.yaml"),
         "--speed", "1", "--obstacles", "0", "--advertise", "127.0.0.1"],
        name="class", cwd=folder, env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        process.wait_for_line("[launch] all", timeout_s=120)
        tokens = dict(line.split(",") for line in (folder / "class-tokens.csv").read_text().splitlines()[1:])
        yield Class(folder, f"http://127.0.0.1:{base}", tokens)
    finally:
        process.stop()


def _pose(room: Class, index: int) -> tuple[float, float, float]:
    pose = room.get("/simulator/robots").json()["poses"][index]
    z, w = pose["orientation"]["z"], pose["orientation"]["w"]
    return pose["position"]["x"], pose["position"]["y"], 2.0 * math.atan2(z, w)


def test_the_world_holds_a_robot_per_student_in_their_namespace(running: Class) -> None:
    assert running.get("/simulator/world").json()["namespaces"] == ["/alice", "/bob"]
    assert running.get("/alice/odom", "alice").status_code == 200
    refused = running.get("/bob/odom", "alice")
    assert refused.status_code == 403 and refused.json()["detail"].startswith("alice may not read /bob/odom")


def test_the_class_page_is_the_instructors(running: Class) -> None:
    assert running.get("/api/class", None).status_code == 401
    student = running.get("/api/class", "alice")
    assert student.status_code == 403 and "the class page is the instructor's" in student.json()["detail"]
    table = running.get("/api/class").json()
    assert [row["name"] for row in table["students"]] == ["alice", "bob"]
    assert "error" not in table["gradebook"] and table["students"][0]["grade"] is None  # no gradebook yet: no grades


def test_a_students_program_drives_their_robot_and_shows_in_the_table(running: Class) -> None:
    program = running.folder / "driver.py"
    program.write_text(WALL_FOLLOWER.format(topic="cmd_vel"))
    env = {**os.environ, "SKYDECK_CORE_URL": running.url, "SKYDECK_TOKEN": running.tokens["alice"]}
    driver = BackgroundProcess([sys.executable, "-m", "services.cli", "run", str(program)], name="alice", cwd=REPO, env=env)
    try:
        alice_before, bob_before = _pose(running, 0), _pose(running, 1)
        wait_until_sync(lambda: _pose(running, 0)[0] > alice_before[0] + 0.2, 60, "alice's robot to drive ahead")
        table = running.get("/api/class").json()["students"]
        alice, bob = table
        assert alice["nodes"] == ["/alice/wall_follower"] and bob["nodes"] == []
        wait_until_sync(
            lambda: running.get("/api/class").json()["students"][0]["last_message_age_s"] is not None, 30, "alice's age"
        )
        assert _pose(running, 1) == pytest.approx(bob_before, abs=1e-3)  # bob's robot never moved
    finally:
        driver.stop()


def test_the_grades_come_from_the_gradebook_when_it_is_written(running: Class) -> None:
    book = {"assignment": "wall_follower", "students": {"alice": {"score": 0.9, "passed": True, "criteria": [
        {"name": "in_band", "passed": True, "figure": "90% of the time", "verdict": "ok"}]}}}  # fmt: skip
    (running.folder / "gradebook.json").write_text(json.dumps(book))
    table = running.get("/api/class").json()
    assert table["assignment"] == "wall_follower"
    alice, bob = table["students"]
    assert alice["grade"]["score"] == 0.9 and alice["grade"]["passed"] is True
    assert alice["grade"]["criteria"][0]["name"] == "in_band" and bob["grade"] is None
    (running.folder / "gradebook.json").write_text("{not json")
    said = running.get("/api/class").json()["gradebook"]
    assert said["error"].startswith(f"cannot read the gradebook {running.folder / 'gradebook.json'}")
