"""The core keeps the last lines of ``/rosout``, so a page that opens or reloads shows what was
said before it came (the dashboard's console, rqt_console's backlog).

    GET /api/rosout?limit=100     the last 100 ``rcl_interfaces/msg/Log`` messages, oldest first

As ROS 1's ``rosout`` node does, the core subscribes to ``/rosout`` for as long as it runs (it
shows in the graph as a subscriber of ``/rosout``): a raw tap on its node's endpoint, one link
per publisher, each frame kept as received and served without being parsed again.
"""

from __future__ import annotations

from collections import deque
from typing import Annotated

from fastapi import APIRouter, Depends, Query, Request
from fastapi.responses import Response

from services.core.core_node import CoreNode
from services.runtime.subscription import RawSubscription
from shared_models.rcl_interfaces import Log

__all__ = ["BACKLOG_LINES", "ROSOUT", "RosoutLog", "router"]

ROSOUT = "/rosout"
BACKLOG_LINES = 500
"""How many lines the core keeps: as many as the dashboard's console shows."""
_QUEUE_SIZE = 1000
"""What each node keeps for the core while it reads (ROS 2's /rosout depth)."""


class RosoutLog:
    """The last ``lines`` messages of ``/rosout``, kept while started."""

    def __init__(self, core: CoreNode, lines: int = BACKLOG_LINES) -> None:
        self._core = core
        self._frames: deque[str] = deque(maxlen=lines)
        self._tap = RawSubscription(ROSOUT, Log, self._frames.append, _QUEUE_SIZE)

    def start(self) -> None:
        self._core.start_reading(ROSOUT, self._tap)

    def stop(self) -> None:
        self._core.stop_reading(ROSOUT, self._tap)

    def latest(self, count: int) -> list[str]:
        """The last ``count`` frames (JSON text), oldest first."""
        kept = len(self._frames)
        return [self._frames[index] for index in range(max(0, kept - count), kept)]


# -- routes -------------------------------------------------------------------------------------

router = APIRouter(prefix="/api", tags=["rosout"])


def _log(request: Request) -> RosoutLog:
    return request.app.state.rosout  # type: ignore[no-any-return]


@router.get("/rosout", response_model=list[Log])
async def rosout_backlog(
    log: Annotated[RosoutLog, Depends(_log)],
    limit: Annotated[int, Query(ge=1, le=BACKLOG_LINES, description="how many of the last lines")] = 100,
) -> Response:
    """The last lines of /rosout the core kept (oldest first), for a console that opens late."""
    return Response("[" + ",".join(log.latest(limit)) + "]", media_type="application/json")
