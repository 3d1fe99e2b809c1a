"""What tf2_web_republisher does for each client: follow some frames, and send those that moved.

A :class:`Watch` is one client's subscription (a goal of either action, or one ``republish_tfs``
request): every ``1 / rate`` seconds it looks up each source frame in the target frame (the
latest transform) and sends the transforms that moved more than ``trans_thres`` metres or turned
more than ``angular_thres`` radians since it last sent them (a threshold of 0 sends every
lookup; a frame's first lookup is always sent), stamped now, as tf2_web_republisher does. A
frame that cannot be looked up yet is left out until it can. Nothing is sent when nothing moved.

The transforms come from one tf2 buffer (:class:`TFSource`: the ``tf2_ros`` BufferCore of
:mod:`services.ros.tf2_ros`, filled by taps on ``/tf`` and ``/tf_static``) that the core keeps
only while some watch runs, so a core without TF clients reads no TF. Its module is imported
then too: it brings the ROS façades, which a core that serves no TF client never loads.
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import services.protocols.rosbridge.clock as clock
from services.protocols.rosbridge.core_host import CoreHost, CoreTap
from shared_models.builtin_interfaces import Time
from shared_models.geometry_msgs import TransformStamped
from shared_models.tf2_msgs import TFMessage

if TYPE_CHECKING:
    from services.ros.tf2_ros.buffer_core import BufferCore

__all__ = ["MAX_RATE_HZ", "TFRequest", "TFSource", "Watch"]

logger = logging.getLogger("skydeck.rosbridge")

MAX_RATE_HZ = 1000.0
"""The fastest a client may ask for its frames (each watch's lookups run on the core's loop)."""
_AUTHORITY = "tf2_web_republisher"
_TF_DEPTH = 100  # as tf2_ros's listener


@dataclass(frozen=True)
class TFRequest:
    """The frames a client follows: the fields TFSubscription's goal and RepublishTFs' request share."""

    source_frames: tuple[str, ...]
    target_frame: str
    angular_thres: float
    trans_thres: float
    rate: float

    @classmethod
    def of(cls, message: Any) -> TFRequest:
        return cls(
            tuple(_clean(frame) for frame in message.source_frames), _clean(message.target_frame),
            float(message.angular_thres), float(message.trans_thres), float(message.rate),
        )  # fmt: skip

    def problem(self) -> str | None:
        """Why the request cannot run (as ROS 2's tf2_web_republisher refuses a goal), or None."""
        if not self.source_frames or not all(self.source_frames):
            return "source_frames must name at least one frame, and no empty one"
        if not self.target_frame:
            return "target_frame must name a frame"
        if not 0 < self.rate <= MAX_RATE_HZ:
            return f"rate must be more than 0 and at most {MAX_RATE_HZ:g} Hz, got {self.rate!r}"
        if not (self.angular_thres >= 0 and self.trans_thres >= 0):
            return "angular_thres and trans_thres must be 0 or more"
        return None


def _clean(frame: str) -> str:
    """tf2 names frames without a leading slash (ROS 1 clients may send one)."""
    return frame[1:] if frame.startswith("/") else frame


class TFSource:
    """The one buffer every watch reads, filled while any watch runs (see the module docstring)."""

    def __init__(self, host: CoreHost) -> None:
        self._host = host
        self.access = host.access
        self._buffer: BufferCore | None = None
        self._taps: list[CoreTap] = []
        self._watches = 0

    def buffer(self) -> BufferCore:
        if self._buffer is None:
            from services.ros.tf2_ros.buffer_core import BufferCore

            self._buffer = BufferCore()
        return self._buffer

    def opened(self) -> None:
        self._watches += 1
        if self._watches == 1:
            buffer = self.buffer()
            self._taps = [
                self._host.create_subscription(TFMessage, "/tf", lambda msg: _fill(buffer.set_transform, msg), _TF_DEPTH),
                self._host.create_subscription(TFMessage, "/tf_static", lambda msg: _fill(buffer.set_transform_static, msg), _TF_DEPTH),
            ]  # fmt: skip

    def closed(self) -> None:
        self._watches -= 1
        if self._watches == 0:
            for tap in self._taps:
                self._host.destroy_subscription(tap)
            self._taps.clear()


def _fill(add: Callable[[TransformStamped, str], bool], msg: TFMessage) -> None:
    for transform in msg.transforms:
        add(transform, _AUTHORITY)


@dataclass
class _Sent:
    translation: tuple[float, float, float]
    rotation: tuple[float, float, float, float]


class Watch:
    """One client's frames, looked up at its rate; ``emit(transforms)`` gets what moved.

    ``wanted()`` is asked at each tick: once it has said no for ``unread_s`` seconds on end (the
    client is gone), the watch ends itself and calls ``on_abandoned``.
    """

    def __init__(
        self, source: TFSource, request: TFRequest, emit: Callable[[list[TransformStamped]], None], *,
        wanted: Callable[[], bool], unread_s: float, on_abandoned: Callable[[], None],
    ) -> None:  # fmt: skip
        self.request = request
        self._source = source
        self._emit = emit
        self._wanted = wanted
        self._unread_s = unread_s
        self._on_abandoned = on_abandoned
        self._sent: dict[str, _Sent] = {}
        self._running = True
        source.opened()
        self._task = asyncio.get_running_loop().create_task(self._run())

    async def _run(self) -> None:
        loop = asyncio.get_running_loop()
        period = 1.0 / self.request.rate
        unread_since: float | None = None
        while True:
            await asyncio.sleep(period)
            if self._wanted():
                unread_since = None
            else:
                unread_since = loop.time() if unread_since is None else unread_since
                if loop.time() - unread_since >= self._unread_s:
                    self._end()
                    self._on_abandoned()
                    return
            try:
                moved = self.moved()
                if moved:
                    self._emit(moved)
            except Exception:  # a bug here must not end the client's subscription unseen
                logger.exception("tf2_web_republisher: a watch of %s failed", ", ".join(self.request.source_frames))

    def moved(self) -> list[TransformStamped]:
        """Each source frame's transform that moved past a threshold since it was last sent."""
        from services.ros.tf2_ros.exceptions import TransformException

        request, buffer = self.request, self._source.buffer()
        now: Time | None = None
        found = []
        for frame in request.source_frames:
            try:
                transform = buffer.lookup_transform_core(request.target_frame, frame, Time())
            except TransformException:
                continue  # not known yet: sent once it is
            t, q = transform.transform.translation, transform.transform.rotation
            current = _Sent((t.x, t.y, t.z), (q.x, q.y, q.z, q.w))
            if not self._moved_enough(self._sent.get(frame), current):
                continue
            self._sent[frame] = current
            now = now or clock.now(self._source.access)
            transform.header.stamp = now
            transform.header.frame_id = request.target_frame
            transform.child_frame_id = frame
            found.append(transform)
        return found

    def _moved_enough(self, sent: _Sent | None, current: _Sent) -> bool:
        request = self.request
        if sent is None or request.trans_thres == 0 or request.angular_thres == 0:
            return True
        return math.dist(sent.translation, current.translation) > request.trans_thres or (
            _angle(sent.rotation, current.rotation) > request.angular_thres
        )

    def stop(self) -> None:
        """End the watch (idempotent)."""
        if self._running:
            self._task.cancel()
            self._end()

    def _end(self) -> None:
        if self._running:
            self._running = False
            self._source.closed()


def _angle(a: tuple[float, float, float, float], b: tuple[float, float, float, float]) -> float:
    """The angle between two rotations as tf's ``Quaternion.angle`` measures it (half the turn
    from one to the other), for unit quaternions; ``q`` and ``-q`` are the same rotation."""
    dot = abs(sum(x * y for x, y in zip(a, b, strict=True)))
    return math.acos(min(1.0, dot))
