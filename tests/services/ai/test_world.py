"""The AI's world tracker: boxes at rest, tied to the world they belong to."""

from __future__ import annotations

from services.ai.world import SETTLED_MESSAGES, WorldTracker
from shared_models.geometry_msgs import Point32, Polygon
from shared_models.ros_workshop import SimWorld


def _boxes(*xy: tuple[float, float], z: float = 1.0) -> Polygon:
    return Polygon(points=[Point32(x=x, y=y, z=z) for x, y in xy])


def _settle(tracker: WorldTracker, *xy: tuple[float, float]) -> None:
    for _ in range(SETTLED_MESSAGES):
        tracker.on_boxes(_boxes(*xy))


def test_ready_needs_a_world_and_boxes_at_rest() -> None:
    tracker = WorldTracker()
    _settle(tracker, (5.0, 5.0))
    assert not tracker.ready.is_set()  # no world yet: progress could not be keyed
    assert tracker.on_world(SimWorld(id="a")) is False  # the first world is not a change
    assert tracker.ready.is_set() and tracker.boxes == [(5.0, 5.0)]
    tracker.on_boxes(_boxes((5.0, 5.0), z=3.0))  # something moved (a box knocked over)
    assert not tracker.ready.is_set()


def test_the_same_world_again_changes_nothing() -> None:
    tracker = WorldTracker()
    tracker.on_world(SimWorld(id="a"))
    _settle(tracker, (5.0, 5.0))
    assert tracker.on_world(SimWorld(id="a")) is False
    assert tracker.ready.is_set()


def test_a_rebuilt_world_of_the_same_seed_waits_for_its_own_boxes() -> None:
    """A restarted simulator with the same seed builds the same boxes: the old world's messages
    still in flight are never taken for the new world's; its boxes are, once seen falling."""
    tracker = WorldTracker()
    tracker.on_world(SimWorld(id="a"))
    _settle(tracker, (5.0, 5.0), (-6.0, 7.0))
    assert tracker.on_world(SimWorld(id="b")) is True
    assert not tracker.ready.is_set()
    _settle(tracker, (5.0, 5.0), (-6.0, 7.0))  # the old world's, on their way through perception
    _settle(tracker, (5.0, 5.0), (-6.0, 7.0))
    assert not tracker.ready.is_set()
    tracker.on_boxes(_boxes((5.0, 5.0), (-6.0, 7.0), z=6.0))  # the new world's, falling
    assert not tracker.ready.is_set()
    _settle(tracker, (5.0, 5.0), (-6.0, 7.0))  # and at rest, where the old ones were
    assert tracker.ready.is_set() and tracker.world is not None and tracker.world.id == "b"


def test_a_new_worlds_boxes_heard_before_its_world_message_are_its_own() -> None:
    """Topics are not ordered one against another: an AI slow to read (a loaded machine) may
    hear a reset's new boxes, fallen and at rest, before the world message; they are the new
    world's, not the old one's in flight."""
    tracker = WorldTracker()
    tracker.on_world(SimWorld(id="a"))
    _settle(tracker, (5.0, 5.0), (-6.0, 7.0))
    tracker.on_boxes(_boxes((1.0, 2.0), (3.0, 4.0), z=6.0))  # the reset's boxes, falling
    _settle(tracker, (1.0, 2.0), (3.0, 4.0))  # and at rest
    assert tracker.on_world(SimWorld(id="b")) is True
    assert tracker.ready.is_set() and tracker.boxes == [(1.0, 2.0), (3.0, 4.0)]
    tracker.on_boxes(_boxes((1.0, 2.0), (3.0, 4.0)))
    assert tracker.ready.is_set() and tracker.world is not None and tracker.world.id == "b"


def test_a_world_without_boxes_is_ready_at_once() -> None:
    tracker = WorldTracker()
    tracker.on_world(SimWorld(id="a", boxes=0))
    _settle(tracker)
    assert tracker.ready.is_set() and tracker.boxes == []
