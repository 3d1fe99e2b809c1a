"""``rclpy.service.Service``: ``node.create_service(Trigger, 'reset', self.handle_reset)``.

A request arrives on the bridge's loop and waits here for the executor that spins the node; the
callback fills in and returns the response it is given (``callback(request, response)``). If
it raises, the caller gets a 500 and the user's traceback is printed; the node keeps running.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from services.ros.bridge import Bridge
from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.waitable import JobQueue, Owner, run_callback
from services.runtime.service import ServiceHandlerError

__all__ = ["Service"]


class Service(JobQueue):
    """Answers one service (made by ``Node.create_service``)."""

    def __init__(
        self, node: Owner, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any],
        callback_group: CallbackGroup | None,
    ) -> None:  # fmt: skip
        super().__init__(node, callback_group, f"the service callback of {srv_name}")
        self.srv_type = srv_type
        self.srv_name = srv_name
        self.callback = callback
        self._destroyed = False

    async def _handle(self, request: Any) -> Any:
        """The SDK's handler (on the bridge's loop): the callback runs in the executor."""
        return await Bridge.hand_off(self.put, lambda: self._answer(request))

    def _answer(self, request: Any) -> Any:
        try:
            return run_callback(self.callback, request, self.srv_type.Response())
        except Exception as error:
            self._node._rclpy_report(error, self.what)
            raise ServiceHandlerError(f"the handler of {self.srv_name} raised {type(error).__name__}: {error}") from None

    def destroy(self) -> None:
        self._destroyed = True
