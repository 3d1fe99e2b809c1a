"""One frame's link to its parent over time, as tf2 keeps it.

A :class:`TimeCache` holds a dynamic link's samples, oldest first, for ``cache_time`` back from
the newest; asked for a time between two samples it interpolates them (linear translation,
slerp rotation), at a sample's own time it returns that sample, and outside them it raises
:class:`ExtrapolationException` with tf2's message. A :class:`StaticCache` holds one sample,
good for every time. Neither locks: the buffer does (:mod:`.buffer_core`).
"""

from __future__ import annotations

import bisect
from typing import NamedTuple

from services.ros.tf2_ros.exceptions import ExtrapolationException
from services.ros.tf2_ros.rigid import Rigid
from services.ros.tf2_ros.times import LATEST, format_time

__all__ = ["Cache", "Sample", "StaticCache", "TimeCache"]


class Sample(NamedTuple):
    """The link at ``stamp`` (ns): ``parent`` and the transform from the frame into it."""

    stamp: int
    parent: str
    transform: Rigid


class TimeCache:
    """A dynamic link's samples (see the module docstring)."""

    def __init__(self, cache_time_ns: int) -> None:
        self._cache_time_ns = cache_time_ns
        self._stamps: list[int] = []
        self._samples: list[Sample] = []

    def insert(self, sample: Sample) -> bool:
        """Keep ``sample``; False (and nothing kept) if it is older than the cache reaches."""
        stamps = self._stamps
        if stamps and sample.stamp < stamps[-1] - self._cache_time_ns:
            return False
        at = bisect.bisect_right(stamps, sample.stamp)
        same = at
        while same and stamps[same - 1] == sample.stamp:
            if self._samples[same - 1] == sample:
                return True  # the same sample again (a latched message heard twice)
            same -= 1
        stamps.insert(at, sample.stamp)
        self._samples.insert(at, sample)
        oldest_kept = bisect.bisect_left(stamps, stamps[-1] - self._cache_time_ns)
        if oldest_kept:
            del stamps[:oldest_kept], self._samples[:oldest_kept]
        return True

    def get(self, time_ns: int) -> Sample:
        """The link at ``time_ns`` (LATEST: the newest sample), interpolated between samples."""
        stamps = self._stamps
        if not stamps:
            raise ExtrapolationException("Lookup would require extrapolation: the buffer holds no data for this frame")
        if time_ns == LATEST:
            return self._samples[-1]
        if len(stamps) == 1:
            if stamps[0] == time_ns:
                return self._samples[0]
            raise ExtrapolationException(
                f"Lookup would require extrapolation at time {format_time(time_ns)}, "
                f"but only time {format_time(stamps[0])} is in the buffer"
            )
        if time_ns > stamps[-1]:
            raise ExtrapolationException(
                f"Lookup would require extrapolation into the future.  Requested time "
                f"{format_time(time_ns)} but the latest data is at time {format_time(stamps[-1])}"
            )
        if time_ns < stamps[0]:
            raise ExtrapolationException(
                f"Lookup would require extrapolation into the past.  Requested time "
                f"{format_time(time_ns)} but the earliest data is at time {format_time(stamps[0])}"
            )
        at = bisect.bisect_left(stamps, time_ns)
        later = self._samples[at]
        if later.stamp == time_ns:
            return later
        earlier = self._samples[at - 1]
        if earlier.parent != later.parent:  # the frame was re-parented between them: no blend
            return earlier
        ratio = (time_ns - earlier.stamp) / (later.stamp - earlier.stamp)
        return Sample(time_ns, earlier.parent, earlier.transform.interpolate(later.transform, ratio))

    def latest(self) -> Sample | None:
        """The newest sample (None while empty)."""
        return self._samples[-1] if self._samples else None

    @property
    def latest_stamp(self) -> int:
        """What tf2 uses for a dynamic link's newest time in latest-common-time (0 while empty)."""
        return self._stamps[-1] if self._stamps else 0

    @property
    def oldest_stamp(self) -> int:
        return self._stamps[0] if self._stamps else 0

    def __len__(self) -> int:
        return len(self._stamps)

    def clear(self) -> None:
        self._stamps.clear()
        self._samples.clear()


class StaticCache:
    """A static link: one sample, whatever time is asked."""

    def __init__(self) -> None:
        self._sample: Sample | None = None

    def insert(self, sample: Sample) -> bool:
        self._sample = sample
        return True

    def get(self, time_ns: int) -> Sample:
        if self._sample is None:
            raise ExtrapolationException("Lookup would require extrapolation: the buffer holds no data for this frame")
        return self._sample

    def latest(self) -> Sample | None:
        return self._sample

    latest_stamp = 0  # static links never limit the latest common time
    oldest_stamp = 0

    def __len__(self) -> int:
        return 0 if self._sample is None else 1

    def clear(self) -> None:
        self._sample = None


Cache = TimeCache | StaticCache
