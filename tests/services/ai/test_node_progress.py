"""Which progress the AI takes for a world: its saved one, or a new tour (and the log line)."""

from __future__ import annotations

import logging

import pytest

from services.ai.node import AiNode
from services.ai.progress import ProgressStore, WorldProgress
from services.runtime import NodeSettings
from shared_models.ros_workshop import SimWorld

BOXES = [(5.0, 5.0), (-6.0, 7.0)]


@pytest.fixture
def ai(tmp_path) -> AiNode:
    return AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path))


def test_a_new_world_gets_a_new_tour(ai, caplog) -> None:
    with caplog.at_level(logging.INFO):
        progress = ai._progress_of(SimWorld(id="w1"), BOXES, again=False)
    assert progress == WorldProgress(world="w1", boxes=2)
    assert "new world w1: 2 boxes" in caplog.text
    assert ai.store.load("w1") == progress  # known from the start: a restart resumes it


def test_a_world_under_way_is_resumed(ai, caplog) -> None:
    ai.store.save(WorldProgress(world="w1", boxes=2, visited=[1, 1, 7]))  # a repeat, an index too far
    with caplog.at_level(logging.INFO):
        progress = ai._progress_of(SimWorld(id="w1"), BOXES, again=True)
    assert progress.visited == [1] and not progress.done
    assert "resuming world w1: 1 of 2 visited" in caplog.text


def test_a_finished_world_stays_finished_unless_asked_again(ai, caplog) -> None:
    ai.store.save(WorldProgress(world="w1", boxes=2, visited=[1, 0], done=True))
    assert ai._progress_of(SimWorld(id="w1"), BOXES, again=False).done  # a restarted AI
    with caplog.at_level(logging.INFO):
        again = ai._progress_of(SimWorld(id="w1"), BOXES, again=True)  # /ai/start
    assert again == WorldProgress(world="w1", boxes=2)
    assert "world w1 was done: a new tour of its 2 boxes" in caplog.text


def test_progress_for_another_box_count_is_not_trusted(ai, caplog) -> None:
    ai.store.save(WorldProgress(world="w1", boxes=5, visited=[0, 1]))
    with caplog.at_level(logging.WARNING):
        progress = ai._progress_of(SimWorld(id="w1"), BOXES, again=False)
    assert progress.visited == [] and "saved progress is for 5 boxes" in caplog.text
