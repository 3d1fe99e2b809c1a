"""Service clients: ``await node.create_client(Trigger, "/control/take_off").call(...)``.

The client asks the core once where the service lives, then calls the hosting node directly, so
calls keep working while the core is away; a failed call forgets the address and asks again.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Generic, TypeVar

from services.runtime.errors import (
    ServiceCallRejectedError,
    ServiceTimeoutError,
    ServiceUnavailableError,
)
from services.runtime.http_client import HttpClient, HttpError, HttpTimeout, HttpUnreachable
from shared_models import Message, ServiceType

__all__ = ["Client"]

R = TypeVar("R", bound=Message)

_WAIT_POLL_S = 0.1


class Client(Generic[R]):
    """Calls one service by name; made by :meth:`Node.create_client`."""

    def __init__(
        self,
        srv_type: type[ServiceType],
        name: str,
        *,
        http: Callable[[], HttpClient],
        core_url: str,
        default_timeout_s: float,
    ) -> None:
        self.srv_type = srv_type
        self.srv_name = name
        self._http = http  # the owning node's client, fetched per call: it exists only while running
        self._core_url = core_url.rstrip("/")
        self._default_timeout_s = default_timeout_s
        self._node_url: str | None = None

    async def call(self, request: Message | None = None, *, timeout_s: float | None = None) -> R:
        """Call the service and return its response (also when ``success`` is false).

        Raises ServiceUnavailableError when no node hosts it or the node is unreachable,
        ServiceTimeoutError after ``timeout_s``, ServiceCallRejectedError on a refused body.
        """
        request = self.srv_type.Request() if request is None else request
        if not isinstance(request, self.srv_type.Request):
            raise TypeError(
                f"{self.srv_name} takes {self.srv_type.Request.__name__}, not {type(request).__name__}"
            )
        timeout_s = self._default_timeout_s if timeout_s is None else timeout_s
        body = request.model_dump_json()
        for attempt in range(2):
            node_url = self._node_url or await self._lookup()
            try:
                reply = await self._http().post(node_url + self.srv_name, body, timeout_s=timeout_s)
            except HttpTimeout:
                raise ServiceTimeoutError(
                    self.srv_name, f"{self.srv_name} did not answer within {timeout_s:g} s"
                ) from None
            except HttpUnreachable as error:
                self._node_url = None  # the node moved or died: ask the core again
                if attempt == 0:
                    continue
                raise ServiceUnavailableError(
                    self.srv_name, f"cannot reach the node hosting {self.srv_name} at {node_url}: {error}"
                ) from None
            if reply.status == 404 and attempt == 0:
                self._node_url = None
                continue
            if reply.status != 200:
                raise ServiceCallRejectedError(
                    self.srv_name, f"{self.srv_name} refused the call ({reply.status}): {reply.text}", reply.status
                )
            return self.srv_type.Response.model_validate_json(reply.body)  # type: ignore[return-value]
        raise ServiceUnavailableError(self.srv_name, f"no node hosts {self.srv_name}")

    def call_async(self, request: Message | None = None, *, timeout_s: float | None = None) -> asyncio.Future[R]:
        """Start a call and return the task (rclpy's ``call_async``)."""
        return asyncio.ensure_future(self.call(request, timeout_s=timeout_s))

    async def service_is_ready(self) -> bool:
        """Whether a live node hosts the service now."""
        try:
            await self._lookup()
        except ServiceUnavailableError:
            return False
        return True

    async def wait_for_service(self, timeout_s: float | None = None) -> bool:
        """Wait until a node hosts the service; False if ``timeout_s`` passes first."""
        try:
            async with asyncio.timeout(timeout_s):
                while not await self.service_is_ready():
                    await asyncio.sleep(_WAIT_POLL_S)
        except TimeoutError:
            return False
        return True

    async def _lookup(self) -> str:
        try:
            reply = await self._http().get(f"{self._core_url}/api/services{self.srv_name}", timeout_s=2.0)
        except HttpError as error:
            raise ServiceUnavailableError(
                self.srv_name, f"cannot ask the core at {self._core_url} where {self.srv_name} is: {error}"
            ) from None
        if reply.status != 200:
            raise ServiceUnavailableError(
                self.srv_name, f"no node hosts {self.srv_name}: see `skydeck service list`"
            )
        self._node_url = str(reply.json()["url"]).rstrip("/")
        return self._node_url
