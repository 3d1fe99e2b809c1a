"""`skydeck run ai`, without --use-sim-time, stamps /ai/status on the simulator's clock."""

from __future__ import annotations

import json
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import free_port_block
from tests.web_ui.system import System

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(90)]


@pytest.fixture
def world(tmp_path: Path) -> Iterator[System]:
    base = free_port_block(5)
    system = System(base)
    try:
        system.start("core", ["core"], base)
        system.start("sim", ["run", "sim", "--speed", "3", "--seed", "1"], base + 1)
        system.start("ai", ["run", "ai"], base + 4, env={"SKYDECK_STATE_DIR": str(tmp_path)})
        yield system
    finally:
        system.stop()


def _latest(system: System, topic: str) -> dict | None:  # type: ignore[type-arg]
    try:
        with urllib.request.urlopen(system.url + topic, timeout=5) as reply:
            return json.loads(reply.read())  # type: ignore[no-any-return]
    except OSError:
        return None


def _seconds(stamp: dict) -> float:  # type: ignore[type-arg]
    return stamp["sec"] + stamp["nanosec"] * 1e-9


def test_the_ai_s_status_is_stamped_in_sim_time(world: System) -> None:
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        status, clock = _latest(world, "/ai/status"), _latest(world, "/clock")
        if status is not None and clock is not None and _seconds(status["header"]["stamp"]) > 0:
            break
        time.sleep(0.1)
    else:
        raise AssertionError(f"no stamped /ai/status: {status}")
    # sim time runs at 3x from zero: a few seconds, never the wall clock's 1.7e9
    assert abs(_seconds(status["header"]["stamp"]) - _seconds(clock)) < 10, (status["header"], clock)
