"""A client of the core's ROS 1 parameter server (:mod:`services.core.parameter_server`).

    server = RosParamClient(http, "http://127.0.0.1:8000")
    await server.set("/ai/visit_radius", 0.4)
    await server.get("/ai")            # {"visit_radius": 0.4}

Names are absolute (the caller resolves ``~private`` and relative names). A name that is not
set raises KeyError, as a dict does; a core that cannot be reached, or refuses, raises
:class:`RosParamError` (:class:`RosParamUnreachable` for no core) with one line that says which.
"""

from __future__ import annotations

import contextlib
import json
from typing import Any

from services.runtime.http_client import HttpClient, HttpError
from shared_models.errors import SkydeckError

__all__ = ["RosParamClient", "RosParamError", "RosParamUnreachable"]

_PATH = "/api/rosparam"
_TIMEOUT_S = 5.0


class RosParamError(SkydeckError):
    """The parameter server refused the request (a bad name or value), or could not be asked."""


class RosParamUnreachable(RosParamError):
    """The core (which holds the parameter server) did not answer."""


class RosParamClient:
    """Reads and writes the core's ROS 1 parameters over ``http``."""

    def __init__(self, http: HttpClient, core_url: str, *, timeout_s: float = _TIMEOUT_S) -> None:
        self._http = http
        self._core_url = core_url.rstrip("/")
        self._timeout_s = timeout_s

    async def get(self, name: str) -> Any:
        """The value of ``name`` (a namespace: the mapping under it); KeyError if unset."""
        return (await self._request("GET", name)).json()["value"]

    async def set(self, name: str, value: Any) -> None:
        """Set ``name`` to ``value`` (a mapping sets the namespace under it)."""
        await self._request("PUT", name, json.dumps({"value": value}))

    async def delete(self, name: str) -> None:
        """Delete ``name`` and all under it; KeyError if unset."""
        await self._request("DELETE", name)

    async def _request(self, method: str, name: str, body: str = "") -> Any:
        url = f"{self._core_url}{_PATH}{'' if name == '/' else name}"
        headers = {"Content-Type": "application/json"} if body else None
        try:
            reply = await self._http.request(method, url, body, timeout_s=self._timeout_s, headers=headers)
        except HttpError as error:
            raise RosParamUnreachable(
                f"cannot reach the parameter server at {self._core_url} ({error}): is the core "
                "running (`skydeck core` or `skydeck launch`)?"
            ) from None
        if reply.status == 404 and method != "PUT":
            raise KeyError(name)
        if reply.status != 200:
            detail = reply.text
            with contextlib.suppress(ValueError, AttributeError):
                detail = reply.json().get("detail", detail)
            raise RosParamError(f"the parameter server refused {method} {name}: {detail}")
        return reply
