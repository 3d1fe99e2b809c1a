"""The core's own routes and the fences: who a request is, what it may do, and ``GET /api/access``.

    @router.post("/api/recordings")
    async def start(visitor: VisitorDep, ...):
        require(visitor, Verb.RECORD, topic)        # 401/403 with the policy's one-line reason

The core's fences are made once, from its settings (:func:`core_fences`). A request is admitted once (:meth:`~services.access.fences.Fences.admit`, from its Bearer header
or ``?token=``); the rules are :mod:`services.access.policy`'s. ``GET /api/access`` says who the
token is and what it may do: ``skydeck run`` takes a student's namespace from it, and the
dashboard its view.
"""

from __future__ import annotations

import logging
from typing import Annotated, Any

from fastapi import APIRouter, Depends, HTTPException, Request

from services.access import Fences, Pass, RateLimits, Verb
from services.core.settings import CoreSettings
from services.runtime.auth import presented_token
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.outbox import Frame
from services.runtime.edge.topic_socket import TopicConnection
from services.runtime.endpoint import TopicEndpoint

__all__ = ["FENCED", "FencedEndpoint", "VisitorDep", "core_fences", "require", "router", "visitor"]

logger = logging.getLogger("skydeck.core")


def core_fences(settings: CoreSettings) -> Fences:
    """The core's fences: a class's (``--class-tokens``, ``--class-rules``) or the process
    token's, with each student's limits; ClassTokensError says in one line what is wrong."""
    limits = RateLimits(
        messages_per_s=settings.student_messages_per_s,
        bytes_per_s=settings.student_bytes_per_s,
        calls_in_flight=settings.student_calls_in_flight,
    )
    fences = Fences.load(
        tokens_file=settings.class_tokens, rules_file=settings.class_rules, process_token=settings.token, limits=limits
    )
    if fences.policy.tokens is not None:
        students = len(fences.policy.tokens.names) - 1
        rules = f", rules from {settings.class_rules}" if settings.class_rules else ""
        logger.info("a class of %d students: tokens from %s%s", students, settings.class_tokens, rules)
    return fences


class FencedEndpoint:
    """A topic the core publishes, as one socket at ``/api/core/TOPIC`` may use it: reading (the
    nodes that link there) and publishing into it, each as the socket's token allows."""

    def __init__(self, endpoint: TopicEndpoint, visitor: Pass) -> None:
        self.name = endpoint.name
        self._endpoint = endpoint
        self._visitor = visitor

    def open(self, connection: TopicConnection) -> Frame | None:
        if connection.outbox is not None:
            self._visitor.check(Verb.READ, self.name)
        return self._endpoint.open(connection)

    def receive_frame(self, connection: TopicConnection, frame: Frame) -> None:
        refusal = self._visitor.refusal(Verb.PUBLISH, self.name)
        if refusal is not None:
            raise FrameRejected(refusal.close_code, str(refusal))
        self._endpoint.receive_frame(connection, frame)

    def close(self, connection: TopicConnection) -> None:
        self._endpoint.close(connection)



def visitor(request: Request) -> Pass:
    """The pass of the request (its token), admitted by the core's fences."""
    fences: Fences = request.app.state.fences
    return fences.admit(presented_token(request))


VisitorDep = Annotated[Pass, Depends(visitor)]

FENCED: dict[int | str, dict[str, Any]] = {
    401: {"description": "A token is needed (the process token's, or in a class your class token)"},
    403: {"description": "The token may not do this (a class's fences: docs/security.md)"},
}
"""The statuses of a fenced route, for its OpenAPI ``responses``."""


def require(visitor: Pass, verb: Verb, name: str) -> None:
    """HTTPException (401 with no token, 403 for a token that may not) unless ``visitor`` may."""
    refusal = visitor.refusal(verb, name)
    if refusal is not None:
        raise HTTPException(refusal.http_status, str(refusal))


router = APIRouter(prefix="/api", tags=["access"])


@router.get("/access")
async def access(request: Request, visitor: VisitorDep) -> dict[str, Any]:
    """Who the presented token is (student, instructor, the process token, or nobody), its
    namespace, and the names it may read, publish, call... (`/**`: everything)."""
    fences: Fences = request.app.state.fences
    return fences.policy.describe(visitor.subject)
