"""``rclpy.client.Client``: ``node.create_client(Trigger, 'reset')``.

``call_async(request)`` returns a :class:`~services.ros.rclpy.task.Future` at once; ``call``
blocks until the answer (from the main thread, another thread, or a callback alike: the
bridge's loop carries the call, so no executor has to spin for it, unlike rclpy).
"""

from __future__ import annotations

from typing import Any

from services.ros.bridge import bridge
from services.ros.rclpy.callback_groups import CallbackGroup
from services.ros.rclpy.task import Future
from services.ros.rclpy.waitable import Owner
from services.runtime.client import Client as RuntimeClient

__all__ = ["Client"]


class Client:
    """Calls one service (made by ``Node.create_client``)."""

    def __init__(self, node: Owner, client: RuntimeClient[Any], callback_group: CallbackGroup | None) -> None:
        self._node = node
        self._client = client
        self.srv_type = client.srv_type
        self.srv_name = client.srv_name
        self.callback_group = callback_group

    def call_async(self, request: Any) -> Future:
        """Send ``request``; the Future gets the response (or the error: nobody serves it...)."""
        self._check(request)
        future = Future()
        future._dispatch = self._node._rclpy_dispatch
        done = bridge.submit(self._client.call(request))

        def finished(outcome: Any) -> None:
            if outcome.cancelled():
                future.cancel()
            elif outcome.exception() is not None:
                future.set_exception(outcome.exception())
            else:
                future.set_result(outcome.result())

        done.add_done_callback(finished)
        return future

    def call(self, request: Any, timeout_sec: float | None = None) -> Any:
        """Send ``request`` and wait for the response; TimeoutError after ``timeout_sec``."""
        self._check(request)
        return bridge.run(self._client.call(request, timeout_s=timeout_sec))

    def service_is_ready(self) -> bool:
        """Whether a node serves it now."""
        return bridge.run(self._client.service_is_ready())

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Wait until a node serves it; False if ``timeout_sec`` passes first (None: forever)."""
        return bridge.run(self._client.wait_for_service(timeout_sec))

    def destroy(self) -> None:
        pass

    def _check(self, request: Any) -> None:
        if not isinstance(request, self.srv_type.Request):
            raise TypeError(
                f"{self.srv_name} takes {self.srv_type.__ros_type__} requests "
                f"({self.srv_type.Request.__name__}), got {type(request).__name__}"
            )
