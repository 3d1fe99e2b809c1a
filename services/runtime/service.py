"""Service servers: ``node.create_service(Trigger, "/control/take_off", handler)``."""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable
from typing import Any

from services.runtime.errors import NodeError, SkydeckError
from services.runtime.lockstep.activity import ACTIVITY
from shared_models import Message, ServiceType

__all__ = ["Service", "ServiceHandlerError"]


class ServiceHandlerError(SkydeckError):
    """The user's handler raised or returned something that is not the response type."""


class Service:
    """A service hosted by a node: a ``POST`` at its name taking ``Request``, answering ``Response``.

    The handler may take ``(request)`` as rospy does and return the response, or
    ``(request, response)`` as rclpy does and fill in and return the response it is given;
    either form may be a coroutine.
    """

    def __init__(self, srv_type: type[ServiceType], name: str, handler: Callable[..., Any]) -> None:
        self.srv_type = srv_type
        self.name = name
        self.handler = handler
        self._passes_response = _positional_arity(handler) >= 2

    async def handle(self, request: Message, logger: logging.Logger) -> Message:
        """Run the handler for ``request`` and return a checked response."""
        response_type = self.srv_type.Response
        try:
            with ACTIVITY.working():  # a lockstep run waits for the handler (services.runtime.lockstep)
                if self._passes_response:
                    result = self.handler(request, response_type())
                else:
                    result = self.handler(request)
                if inspect.isawaitable(result):
                    result = await result
        except ServiceHandlerError:
            raise  # already reported where it happened (a façade prints the user's traceback)
        except Exception as error:
            logger.exception("handler of %s raised", self.name)
            raise ServiceHandlerError(f"handler of {self.name} raised {type(error).__name__}: {error}") from error
        if isinstance(result, dict):
            result = response_type.model_validate(result)
        if not isinstance(result, response_type):
            raise ServiceHandlerError(
                f"handler of {self.name} returned {type(result).__name__}, expected {response_type.__name__}"
            )
        return result


def _positional_arity(handler: Callable[..., Any]) -> int:
    try:
        parameters = inspect.signature(handler).parameters.values()
    except (TypeError, ValueError) as error:
        raise NodeError(f"service handler {handler!r} has no inspectable signature") from error
    kinds = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    if any(p.kind is inspect.Parameter.VAR_POSITIONAL for p in parameters):
        return 1
    return sum(1 for p in parameters if p.kind in kinds and p.default is inspect.Parameter.empty)
