"""tf2's BufferCore: the tree of frames, each a link to its parent over time, and lookups
through it, as tf2 answers them.

A lookup from ``source`` to ``target`` walks up from each to the root of its tree, composing
the links at the asked time; the result maps points of ``source`` into ``target``. Time zero
asks for the newest time every dynamic link on the path has data for (tf2's "latest common
time"). Errors are tf2's classes and words (:mod:`.exceptions`): an unknown frame a
LookupException, two unconnected trees a ConnectivityException, a time outside a link's data an
ExtrapolationException naming the frames.

Thread-safe: messages arrive on Skydeck's event loop (the listener's subscriptions) while the
program's threads look up; one lock guards the frames, and a condition on it wakes the waits of
:class:`~.buffer.Buffer` when data arrives.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import Any

from services.ros.tf2_ros.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
)
from services.ros.tf2_ros.rigid import IDENTITY, Rigid
from services.ros.tf2_ros.time_cache import Cache, Sample, StaticCache, TimeCache
from services.ros.tf2_ros.times import LATEST, duration_ns, format_time, stamp, time_ns
from shared_models.geometry_msgs import Quaternion, Transform, TransformStamped, Vector3
from shared_models.std_msgs import Header

__all__ = ["DEFAULT_CACHE_TIME_S", "BufferCore"]

_log = logging.getLogger(__name__.rpartition(".")[0])

DEFAULT_CACHE_TIME_S = 10.0
"""How far back a buffer keeps each link's data, as tf2's default."""
_MAX_GRAPH_DEPTH = 1000
_QUATERNION_TOLERANCE = 10e-3  # tf2 ignores a rotation whose squared norm is further from 1


class BufferCore:
    """The frames and their links (see the module docstring); ``cache_time`` a Duration or seconds."""

    def __init__(self, cache_time: Any = None) -> None:
        self._cache_time_ns = duration_ns(cache_time, "cache_time") if cache_time is not None else int(DEFAULT_CACHE_TIME_S * 1e9)
        if self._cache_time_ns <= 0:
            raise InvalidArgumentException(f"cache_time must be positive, got {cache_time!r}")
        self._frames: dict[str, Cache | None] = {}  # a root (or a parent heard of only) has no cache
        self._authority: dict[str, str] = {}
        self._old_data_warned: set[str] = set()
        self._lock = threading.Lock()
        self._arrived = threading.Condition(self._lock)
        self._new_data_callbacks: list[Callable[[], None]] = []

    # -- data in ----------------------------------------------------------------------------

    def set_transform(self, transform: TransformStamped, authority: str) -> bool:
        """Add a dynamic link's sample; False (with tf2's logged reason) if it is refused."""
        return self._set(transform, authority, static=False)

    def set_transform_static(self, transform: TransformStamped, authority: str) -> bool:
        """Set a static link (good at every time)."""
        return self._set(transform, authority, static=True)

    def _set(self, transform: TransformStamped, authority: str, *, static: bool) -> bool:
        if not isinstance(transform, TransformStamped):
            raise TypeError(f"set_transform takes a geometry_msgs TransformStamped, got {type(transform).__name__}")
        child = _strip_slash(transform.child_frame_id)
        parent = _strip_slash(transform.header.frame_id)
        rotation = transform.transform.rotation
        if child == parent:
            _log.error(
                'TF_SELF_TRANSFORM: Ignoring transform from authority "%s" with frame_id and child_frame_id '
                '"%s" because they are the same', authority, child,
            )  # fmt: skip
            return False
        if not child:
            _log.error('TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "%s" because child_frame_id not set', authority)
            return False
        if not parent:
            _log.error(
                'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "%s" from authority "%s" because frame_id not set',
                child, authority,
            )  # fmt: skip
            return False
        norm = rotation.x**2 + rotation.y**2 + rotation.z**2 + rotation.w**2
        if abs(norm - 1.0) >= _QUATERNION_TOLERANCE:
            _log.error(
                'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "%s" from authority "%s" because '
                "of an invalid quaternion in the transform (%f %f %f %f)",
                child, authority, rotation.x, rotation.y, rotation.z, rotation.w,
            )  # fmt: skip
            return False
        sample = Sample(transform.header.stamp.to_nsec(), parent, Rigid.from_msg(transform.transform))
        with self._lock:
            cache = self._frames.get(child)
            if cache is None or isinstance(cache, StaticCache) != static:
                cache = StaticCache() if static else TimeCache(self._cache_time_ns)
                self._frames[child] = cache
            self._frames.setdefault(parent, None)
            kept = cache.insert(sample)
            if kept:
                self._authority[child] = authority
                self._arrived.notify_all()
            callbacks = list(self._new_data_callbacks)
        if not kept:
            if child not in self._old_data_warned:  # once per frame: a stale broadcaster repeats it
                self._old_data_warned.add(child)
                _log.warning(
                    "TF_OLD_DATA ignoring data from the past for frame %s at time %s according to authority %s\n"
                    "Possible reasons are listed at http://wiki.ros.org/tf/Errors%%20explained",
                    child, format_time(sample.stamp), authority,
                )  # fmt: skip
            return False
        for callback in callbacks:
            callback()
        return True

    def clear(self) -> None:
        """Forget every link's data (the frames stay known)."""
        with self._lock:
            for cache in self._frames.values():
                if cache is not None:
                    cache.clear()

    # -- lookups ----------------------------------------------------------------------------

    def lookup_transform_core(self, target_frame: str, source_frame: str, time: Any) -> TransformStamped:
        """The transform from ``source_frame`` into ``target_frame`` at ``time`` (0: the latest), now."""
        time_value = time_ns(time)
        with self._lock:
            rigid, used = self._lookup(target_frame, source_frame, time_value)
        return _message(rigid, used, target_frame, source_frame)

    def lookup_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> TransformStamped:
        """``source_frame`` at ``source_time`` into ``target_frame`` at ``target_time``, through
        ``fixed_frame``, the frame taken not to move in between."""
        target_ns, source_ns = time_ns(target_time, "target_time"), time_ns(source_time, "source_time")
        with self._lock:
            for frame, what in ((target_frame, "target_frame"), (source_frame, "source_frame"), (fixed_frame, "fixed_frame")):
                self._validate(f"lookupTransform argument {what}", frame)
            source_to_fixed, _ = self._lookup(fixed_frame, source_frame, source_ns)
            fixed_to_target, used = self._lookup(target_frame, fixed_frame, target_ns)
        return _message(source_to_fixed.then(fixed_to_target), used, target_frame, source_frame)

    def can_transform_core(self, target_frame: str, source_frame: str, time: Any) -> tuple[bool, str]:
        """(whether the lookup would succeed now, tf2's reason when not)."""
        time_value = time_ns(time)
        with self._lock:
            return self._can(target_frame, source_frame, time_value, "canTransform")

    def can_transform_full_core(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> tuple[bool, str]:
        target_ns, source_ns = time_ns(target_time, "target_time"), time_ns(source_time, "source_time")
        with self._lock:
            for frame, what in ((target_frame, "target_frame"), (source_frame, "source_frame"), (fixed_frame, "fixed_frame")):
                error = self._frame_error(f"canTransform argument {what}", frame)
                if error:
                    return False, error
            ok, error = self._can(target_frame, fixed_frame, target_ns, "canTransform")
            if not ok:
                return ok, error
            return self._can(fixed_frame, source_frame, source_ns, "canTransform")

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        """The newest time both frames have data for (a ``builtin_interfaces/msg/Time``)."""
        with self._lock:
            self._validate("getLatestCommonTime argument target_frame", target_frame)
            self._validate("getLatestCommonTime argument source_frame", source_frame)
            return stamp(self._latest_common_time(target_frame, source_frame))

    # -- what is known ----------------------------------------------------------------------

    def all_frames_as_string(self) -> str:
        """``Frame X exists with parent Y.`` per frame, as tf2 prints them."""
        with self._lock:
            return "".join(
                f"Frame {frame} exists with parent {latest.parent if latest else 'NO_PARENT'}.\n"
                for frame, cache in self._frames.items()
                if cache is not None
                for latest in [cache.latest()]
            )

    def all_frames_as_yaml(self, current_time: Any = None) -> str:
        """Each frame's parent, authority, rate and data span, as tf2's ``allFramesAsYAML``."""
        now = time_ns(current_time) if current_time is not None else LATEST
        lines = []
        with self._lock:
            for frame, cache in self._frames.items():
                latest = cache.latest() if cache is not None else None
                if cache is None or latest is None:
                    continue
                span_ns = cache.latest_stamp - cache.oldest_stamp
                rate = len(cache) * 1e9 / max(span_ns, 100_000)
                lines += [
                    f"{frame}: ",
                    f"  parent: '{latest.parent}'",
                    f"  broadcaster: '{self._authority.get(frame, 'no recorded authority')}'",
                    f"  rate: {rate:.3f}",
                    f"  most_recent_transform: {format_time(cache.latest_stamp)}",
                    f"  oldest_transform: {format_time(cache.oldest_stamp)}",
                ]
                if now != LATEST:
                    lines.append(f"  transform_delay: {(now - cache.latest_stamp) / 1e9:.3f}")
                lines.append(f"  buffer_length: {span_ns / 1e9:.3f}")
        return "\n".join(lines) + "\n" if lines else "[]"

    def frame_exists(self, frame_id: str) -> bool:
        with self._lock:
            return frame_id in self._frames

    def frame_names(self) -> list[str]:
        with self._lock:
            return list(self._frames)

    # tf2_py's names for the last two (ROS 1's tf and older code call them)
    _frameExists = frame_exists
    _getFrameStrings = frame_names

    # -- waiting (for Buffer) ---------------------------------------------------------------

    def _wait_for(self, ready: Callable[[], bool], timeout_s: float) -> bool:
        """Block until ``ready()`` (checked under the lock as data arrives) or ``timeout_s``."""
        with self._arrived:
            return self._arrived.wait_for(ready, timeout_s)

    def _add_new_data_callback(self, callback: Callable[[], None]) -> None:
        with self._lock:
            self._new_data_callbacks.append(callback)

    def _remove_new_data_callback(self, callback: Callable[[], None]) -> None:
        with self._lock:
            if callback in self._new_data_callbacks:
                self._new_data_callbacks.remove(callback)

    # -- the walk (callers hold the lock) ---------------------------------------------------

    def _can(self, target: str, source: str, time: int, verb: str) -> tuple[bool, str]:
        if target == source:
            return True, ""
        for frame, what in ((target, "target_frame"), (source, "source_frame")):
            error = self._frame_error(f"{verb} argument {what}", frame)
            if error:
                return False, error
        try:
            self._walk(target, source, time)
        except TransformException as error:
            return False, str(error)
        return True, ""

    def _lookup(self, target: str, source: str, time: int) -> tuple[Rigid, int]:
        if target == source:
            cache = self._frames.get(target)
            return IDENTITY, (cache.latest_stamp if cache is not None and time == LATEST else time)
        self._validate("lookupTransform argument target_frame", target)
        self._validate("lookupTransform argument source_frame", source)
        return self._walk(target, source, time)

    def _validate(self, what: str, frame: str) -> None:
        if not isinstance(frame, str):
            raise InvalidArgumentException(f"a frame id is a string, got {type(frame).__name__} {frame!r} ({what})")
        if not frame:
            raise InvalidArgumentException(f'Invalid argument "{frame}" passed to {what} - in tf2 frame_ids cannot be empty')
        if frame.startswith("/"):
            raise InvalidArgumentException(
                f"Invalid argument \"{frame}\" passed to {what} - in tf2 frame_ids cannot start with a '/'"
            )
        if frame not in self._frames:
            raise LookupException(f'"{frame}" passed to {what} does not exist. ')

    def _frame_error(self, what: str, frame: str) -> str:
        """tf2's words for a frame canTransform cannot use ("" when it can)."""
        if not isinstance(frame, str):
            return f"a frame id is a string, got {type(frame).__name__} {frame!r} ({what})"
        reason = (
            "in tf2 frame_ids cannot be empty" if not frame
            else "in tf2 frame_ids cannot start with a '/'" if frame.startswith("/")
            else "frame does not exist" if frame not in self._frames
            else ""
        )  # fmt: skip
        return f'Invalid frame ID "{frame}" passed to {what} - {reason}' if reason else ""

    def _walk(self, target: str, source: str, time: int) -> tuple[Rigid, int]:
        """The transform from ``source`` into ``target`` at ``time``, and the time used."""
        if time == LATEST:
            time = self._latest_common_time(target, source)
        # Up from the source to the root of its tree (or to where its data runs out).
        to_top = IDENTITY
        frame = top = source
        source_error = ""
        for _ in range(_MAX_GRAPH_DEPTH):
            cache = self._frames.get(frame)
            if cache is None:
                top = frame
                break
            try:
                sample = cache.get(time)
            except ExtrapolationException as error:
                top, source_error = frame, str(error)
                break
            if frame == target:  # the target is an ancestor of the source
                return to_top, time
            to_top = to_top.then(sample.transform)
            top, frame = frame, sample.parent
        else:
            raise self._loop_error()
        # Up from the target until it meets that top.
        target_to_top = IDENTITY
        frame = target
        for _ in range(_MAX_GRAPH_DEPTH):
            if frame == top:
                break
            cache = self._frames.get(frame)
            if cache is None:
                break
            try:
                sample = cache.get(time)
            except ExtrapolationException as error:
                raise ExtrapolationException(f"{error}{_between(source, target)}") from None
            if frame == source:  # the source is an ancestor of the target
                return target_to_top.inverse(), time
            target_to_top = target_to_top.then(sample.transform)
            frame = sample.parent
        else:
            raise self._loop_error()
        if frame != top:
            if source_error:
                raise ExtrapolationException(f"{source_error}{_between(source, target)}")
            raise ConnectivityException(_unconnected(source, target))
        return to_top.then(target_to_top.inverse()), time

    def _latest_common_time(self, target: str, source: str) -> int:
        """The newest time every dynamic link between the two frames has data for (0: all static)."""
        if source == target:
            cache = self._frames.get(source)
            return cache.latest_stamp if cache is not None else 0
        source_chain: list[tuple[int, str]] = []  # (the link's newest stamp, its parent), upwards
        frame, newest = source, None
        for _ in range(_MAX_GRAPH_DEPTH):
            link = self._newest_link(frame)
            if link is None:
                break
            newest = _older(newest, link[0])
            source_chain.append(link)
            frame = link[1]
            if frame == target:
                return newest or 0
        else:
            raise self._loop_error()
        parents = {parent for _, parent in source_chain}
        frame, newest, common_parent = target, None, None
        for _ in range(_MAX_GRAPH_DEPTH):
            link = self._newest_link(frame)
            if link is None:
                break
            newest = _older(newest, link[0])
            if link[1] in parents:
                common_parent = link[1]
                break
            frame = link[1]
            if frame == source:
                return newest or 0
        else:
            raise self._loop_error()
        if common_parent is None:
            raise ConnectivityException(_unconnected(source, target))
        for latest_stamp, parent in source_chain:
            newest = _older(newest, latest_stamp)
            if parent == common_parent:
                break
        return newest or 0

    def _newest_link(self, frame: str) -> tuple[int, str] | None:
        """The newest stamp of ``frame``'s link to its parent, and the parent (None: a root, or a
        frame nobody broadcasts)."""
        cache = self._frames.get(frame)
        latest = cache.latest() if cache is not None else None
        if cache is None or latest is None:
            return None
        return cache.latest_stamp, latest.parent

    def _loop_error(self) -> LookupException:
        frames = "".join(
            f"Frame {frame} exists with parent {latest.parent}.\n"
            for frame, cache in self._frames.items()
            if cache is not None and (latest := cache.latest()) is not None
        )
        return LookupException(f"The tf tree is invalid because it contains a loop.\n{frames}")


def _older(newest: int | None, latest_stamp: int) -> int | None:
    """tf2's running minimum of the links' newest stamps; a static link (0) does not count."""
    if latest_stamp == 0:
        return newest
    return latest_stamp if newest is None else min(newest, latest_stamp)


def _between(source: str, target: str) -> str:
    return f", when looking up transform from frame [{source}] to frame [{target}]"


def _unconnected(source: str, target: str) -> str:
    return (
        f"Could not find a connection between '{target}' and '{source}' because they are not part of the "
        "same tree.Tf has two or more unconnected trees."
    )


def _strip_slash(frame_id: str) -> str:
    return frame_id[1:] if frame_id.startswith("/") else frame_id


def _message(rigid: Rigid, time: int, target: str, source: str) -> TransformStamped:
    (tx, ty, tz), (qx, qy, qz, qw) = rigid
    return TransformStamped(
        header=Header(stamp=stamp(time), frame_id=target),
        child_frame_id=source,
        transform=Transform(translation=Vector3(x=tx, y=ty, z=tz), rotation=Quaternion(x=qx, y=qy, z=qz, w=qw)),
    )
