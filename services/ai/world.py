"""Which world the AI is in, and that world's boxes once they are at rest.

The simulator names each build of its world on ``/simulator/world``; the boxes come from
perception (``/perception/boxes``, a Polygon, which cannot say which world they belong to). The
tracker ties the two together:

- boxes count as at rest when ``SETTLED_MESSAGES`` consecutive messages agree within
  ``SETTLED_TOLERANCE_M`` (a plan, or saved progress, made on falling boxes would be wrong);
- when the world changes under a running AI, box messages of the old world may still be on their
  way through perception. The new world's boxes are dropped from 4-8 m, so they are accepted
  only once a message differs from where the old world's boxes first came to rest (its boxes
  falling): an old world's boxes are never taken for the new one's, even when the same seed
  builds the same boxes;
- two topics are not ordered one against the other: an AI that was slow to read (a loaded
  machine) may hear the new world's boxes, even at rest, before the world message. Box messages
  heard before it that differ from where the old world's boxes first came to rest are kept as
  the new world's (the drone flies above the boxes: a world's boxes do not move once at rest).
"""

from __future__ import annotations

import asyncio
import math

from shared_models.geometry_msgs import Polygon
from shared_models.ros_workshop import SimWorld

__all__ = ["SETTLED_MESSAGES", "SETTLED_TOLERANCE_M", "WorldTracker"]

SETTLED_MESSAGES = 3
SETTLED_TOLERANCE_M = 0.02

Boxes3 = list[tuple[float, float, float]]


class WorldTracker:
    """The current world (``world``) and its boxes at rest (``boxes``; ``ready`` is set while
    both are known)."""

    def __init__(self) -> None:
        self.world: SimWorld | None = None
        self.boxes: list[tuple[float, float]] = []
        self.ready = asyncio.Event()
        self._recent: list[Boxes3] = []
        self._first_at_rest: Boxes3 | None = None  # this world's boxes, where they first came to rest
        self._old_world_boxes: Boxes3 | None = None

    def on_world(self, msg: SimWorld) -> bool:
        """Take a world message; True when it names a new world after another (a reset, or a
        restarted simulator), which ends whatever mission was flying in the old one."""
        if self.world is not None and msg.id == self.world.id:
            return False
        changed = self.world is not None
        self.world = msg
        heard, self._recent = self._recent, []
        if changed:
            at_rest = self._first_at_rest
            self._old_world_boxes = at_rest if at_rest is not None else (heard[-1] if heard else None)
            self._first_at_rest = None
        for boxes in heard:  # boxes heard before the world message: this world's, past the gate
            self._take(boxes)
        self._judge()
        return changed

    def on_boxes(self, msg: Polygon) -> None:
        """Take a box message (perception's, in the simulator's order: indices are box ids)."""
        self._take([(p.x, p.y, p.z) for p in msg.points])

    def _take(self, boxes: Boxes3) -> None:
        if self._old_world_boxes is not None:
            if _agree(boxes, self._old_world_boxes):
                return  # still the old world's, on its way through perception
            self._old_world_boxes = None
        self._recent = [*self._recent[1 - SETTLED_MESSAGES :], boxes]
        self._judge()

    def _judge(self) -> None:
        recent = self._recent
        if self.world is not None and len(recent) >= SETTLED_MESSAGES and all(_agree(b, recent[0]) for b in recent[1:]):
            self.boxes = [(x, y) for x, y, _ in recent[-1]]
            if self._first_at_rest is None:
                self._first_at_rest = recent[-1]
            self.ready.set()
        else:
            self.ready.clear()


def _agree(boxes: Boxes3, other: Boxes3) -> bool:
    """The same boxes, none more than the tolerance apart."""
    return len(boxes) == len(other) and all(
        math.dist(a, b) <= SETTLED_TOLERANCE_M for a, b in zip(boxes, other, strict=True)
    )
