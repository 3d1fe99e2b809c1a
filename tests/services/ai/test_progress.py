"""The AI's progress file: per world id, the last few worlds only, atomic, tolerant of a damaged
or unwritable file."""

from __future__ import annotations

import json
import logging

from services.ai.progress import FILE_NAME, KEEP_WORLDS, ProgressStore, WorldProgress


def test_save_and_load_per_world(tmp_path) -> None:
    store = ProgressStore(tmp_path)
    store.save(WorldProgress(world="a1", boxes=8, visited=[1, 0]))
    store.save(WorldProgress(world="b2", boxes=3, visited=[0], done=True))
    again = ProgressStore(tmp_path)  # a restarted AI reads what the first one wrote
    assert again.load("a1") == WorldProgress(world="a1", boxes=8, visited=[1, 0])
    assert again.load("b2") == WorldProgress(world="b2", boxes=3, visited=[0], done=True)
    assert again.load("c3") is None
    assert not list(tmp_path.glob(".ai_progress.*"))  # no temporary file left behind


def test_loaded_progress_is_a_copy(tmp_path) -> None:
    store = ProgressStore(tmp_path)
    store.save(WorldProgress(world="a1", boxes=8))
    loaded = store.load("a1")
    assert loaded is not None
    loaded.visited.append(4)
    assert store.load("a1") == WorldProgress(world="a1", boxes=8)


def test_only_the_last_few_worlds_are_kept(tmp_path) -> None:
    store = ProgressStore(tmp_path)
    for run in range(KEEP_WORLDS + 4):
        store.save(WorldProgress(world=f"w{run}", boxes=8, visited=[0, 1], done=True))
    store.save(WorldProgress(world="w5", boxes=8, visited=[0, 1, 2]))  # saved again: now the newest
    kept = [w["world"] for w in json.loads((tmp_path / FILE_NAME).read_text())["worlds"]]
    assert len(kept) == KEEP_WORLDS
    assert kept[-1] == "w5" and "w0" not in kept and "w8" in kept


def test_damaged_file_is_ignored_with_a_warning_and_replaced(tmp_path, caplog) -> None:
    (tmp_path / FILE_NAME).write_text("{not json")
    store = ProgressStore(tmp_path)
    with caplog.at_level(logging.WARNING):
        assert store.load("anything") is None
        assert store.load("anything") is None
    assert caplog.text.count("ignoring the AI's progress file") == 1  # said once, not at every load
    store.save(WorldProgress(world="anything", boxes=2, visited=[1]))
    assert ProgressStore(tmp_path).load("anything") == WorldProgress(world="anything", boxes=2, visited=[1])


def test_a_file_of_another_shape_is_ignored(tmp_path) -> None:
    # The old format: visited indices under a digest of the box positions.
    (tmp_path / FILE_NAME).write_text(json.dumps({"3f2a9c": [0, 1, 2]}))
    warnings: list[str] = []
    store = ProgressStore(tmp_path, warn=warnings.append)
    assert store.load("3f2a9c") is None
    assert len(warnings) == 1 and "not a progress file of this version" in warnings[0]


def test_an_unreadable_or_unwritable_file_is_reported_and_nothing_raises(tmp_path) -> None:
    (tmp_path / FILE_NAME).mkdir()  # reading it fails, and so does replacing it
    warnings: list[str] = []
    store = ProgressStore(tmp_path, warn=warnings.append)
    assert store.load("a1") is None
    store.save(WorldProgress(world="a1", boxes=8, visited=[0]))
    store.save(WorldProgress(world="a1", boxes=8, visited=[0, 1]))
    assert store.load("a1") == WorldProgress(world="a1", boxes=8, visited=[0, 1])  # kept in memory
    assert any("cannot read it" in w for w in warnings)
    assert sum("cannot save" in w for w in warnings) == 1
