"""The ROS time of the core's rosbridge side: ``/clock`` while a simulator publishes it, else the
wall clock (as a ROS node with ``use_sim_time`` reads it when a clock runs).

``now`` is what the core knows at once (the ``/clock`` message it holds because someone reads
it); ``current`` may also ask ``/clock``'s publisher (rosapi's ``get_time``, which a client
calls to learn the time).
"""

from __future__ import annotations

import time

from services.core.access import CoreAccess
from shared_models.builtin_interfaces import Time

__all__ = ["current", "now"]

_CLOCK = "/clock"


def now(access: CoreAccess) -> Time:
    """The time now, without waiting: ``/clock``'s latest message the core holds, else the wall clock."""
    if access.registry.publishers(_CLOCK):
        endpoint = access.core.endpoint(_CLOCK)
        frame = endpoint.latest_frame if endpoint is not None else None
        if frame is not None:
            found = _time_of(frame)
            if found is not None:
                return found
    return Time.from_nsec(time.time_ns())


async def current(access: CoreAccess) -> Time:
    """The time now, asking ``/clock``'s publisher for its latest message if the core has none."""
    if access.registry.publishers(_CLOCK):
        frame = await access.gateway.latest_frame(_CLOCK)
        if frame is not None:
            found = _time_of(frame)
            if found is not None:
                return found
    return Time.from_nsec(time.time_ns())


def _time_of(frame: str | bytes) -> Time | None:
    try:
        return Time.model_validate_json(frame)
    except ValueError:
        return None  # a /clock of another type: the wall clock answers
