"""The AI's progress file: per world, atomic, tolerant of a damaged file."""

from __future__ import annotations

from services.ai.progress import ProgressStore, world_key


def test_save_and_load_per_world(tmp_path) -> None:
    store = ProgressStore(tmp_path)
    first, second = world_key([(5.0, 6.0), (-7.0, 8.0)]), world_key([(9.0, 9.0)])
    store.save(first, [1, 0])
    store.save(second, [0])
    assert store.load(first) == [1, 0] and store.load(second) == [0]
    assert store.load(world_key([(1.0, 1.0)])) == []
    assert not list(tmp_path.glob(".ai_progress.*"))  # no temporary file left behind


def test_world_key_ignores_centimetre_jitter() -> None:
    assert world_key([(5.02, 6.01)]) == world_key([(4.97, 5.99)])
    assert world_key([(5.0, 6.0)]) != world_key([(6.0, 5.0)])


def test_damaged_file_reads_as_empty(tmp_path) -> None:
    store = ProgressStore(tmp_path)
    store.path.write_text("{not json")
    assert store.load("anything") == []
    store.save("anything", [3])
    assert store.load("anything") == [3]
