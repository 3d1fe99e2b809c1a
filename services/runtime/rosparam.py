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
import re
from typing import Any

from services.runtime.http_client import HttpClient, HttpError
from shared_models.errors import SkydeckError

__all__ = [
    "PARAMETER_TOKEN",
    "RosParamClient",
    "RosParamError",
    "RosParamUnreachable",
    "check_parameter_value",
    "parameter_tokens",
]

_PATH = "/api/rosparam"
_TIMEOUT_S = 5.0
PARAMETER_TOKEN = r"[A-Za-z_][A-Za-z0-9_]*"
"""One part of a parameter name, between slashes (a regular expression): letters, digits and _."""
_TOKEN = re.compile(PARAMETER_TOKEN)
_MAX_DEPTH = 32


def parameter_tokens(name: str) -> list[str]:
    """The parts of an absolute parameter name (``/ai/visit_radius`` -> ``["ai", "visit_radius"]``;
    ``/`` -> ``[]``); ValueError for a name that is not one."""
    if not name.startswith("/"):
        raise ValueError(f"parameter name {name!r} must be absolute (start with /)")
    tokens = [token for token in name.split("/") if token]
    for token in tokens:
        if not _TOKEN.fullmatch(token):
            raise ValueError(f"parameter name {name!r}: {token!r} is not a name (letters, digits and _)")
    return tokens


def check_parameter_value(value: Any, name: str, depth: int = 0) -> None:
    """ValueError unless ``value`` is what ROS 1's parameter server holds: a bool, number,
    string, list of those, or a mapping of names to those (a namespace)."""
    if depth > _MAX_DEPTH:
        raise ValueError(f"{name}: nested deeper than {_MAX_DEPTH} levels")
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str) or not _TOKEN.fullmatch(key):
                raise ValueError(f"{name}: {key!r} is not a parameter name (letters, digits and _)")
            check_parameter_value(item, f"{name.rstrip('/')}/{key}", depth + 1)
    elif isinstance(value, list):
        for item in value:
            check_parameter_value(item, name, depth + 1)
    elif value is None or not isinstance(value, bool | int | float | str):
        raise ValueError(f"{name}: {value!r} is not a parameter value (a number, bool, string, list or mapping)")


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
