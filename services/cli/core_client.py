"""Talking to the core from the CLI: its URL, JSON requests, and readable errors."""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from services.cli.errors import CliError
from services.cli.settings import cli_settings
from services.runtime.http_client import HttpError, HttpReply, HttpTimeout, request_once

__all__ = [
    "auth_headers", "core_url", "error_detail", "get", "get_json", "node_settings", "post_json", "unknown_name", "ws_url",
]  # fmt: skip


def core_url() -> str:
    """The core's URL: ``SKYDECK_CORE_URL`` or the default ``http://127.0.0.1:8000``."""
    return cli_settings().core_url.rstrip("/")


def auth_headers() -> dict[str, str]:
    """The Authorization header when ``SKYDECK_TOKEN`` is set."""
    token = cli_settings().token
    return {"Authorization": f"Bearer {token}"} if token else {}


def ws_url(path: str, **query: Any) -> str:
    """The core's WebSocket URL for ``path`` with query options (None values left out)."""
    base = core_url()
    scheme, _, rest = base.partition("://")
    params = "&".join(f"{k}={v}" for k, v in query.items() if v is not None)
    return f"{'wss' if scheme == 'https' else 'ws'}://{rest}{path}" + (f"?{params}" if params else "")


def node_settings() -> Any:
    """The settings of a node the CLI runs itself (a recorder, an action client): the
    process's, on a port of its own choosing."""
    from services.runtime.settings import node_settings as process_node_settings

    return process_node_settings().model_copy(update={"port": 0})


def _unreachable(error: Exception) -> CliError:
    return CliError(
        f"cannot reach the core at {core_url()} ({error}): is it running? "
        "start it with `skydeck core` (or `make up`), or set SKYDECK_CORE_URL"
    )


def get(url: str, *, timeout_s: float) -> HttpReply:
    """GET ``url`` (a node's or the core's) with the token; HttpError when no reply came."""
    return request_once("GET", url, timeout_s=timeout_s, headers=auth_headers())


def get_json(path: str, *, missing: str | Callable[[], str] | None = None) -> Any:
    """GET ``path`` on the core; a 404 raises CliError(``missing``) when given (a callable is
    asked only then: what to say may take another request, as the nearest names do)."""
    try:
        reply = get(core_url() + path, timeout_s=5.0)
    except HttpError as error:
        raise _unreachable(error) from None
    if reply.status == 404 and missing is not None:
        raise CliError(missing if isinstance(missing, str) else missing())
    if reply.status != 200:
        raise CliError(f"the core answered {reply.status} for {path}: {error_detail(reply)}")
    return reply.json()


def post_json(path: str, body: Any, *, timeout_s: float) -> HttpReply:
    """POST ``body`` as JSON to ``path`` on the core and return the reply, whatever its status."""
    try:
        payload = json.dumps(body, ensure_ascii=False, separators=(",", ":"), allow_nan=False).encode()
    except (TypeError, ValueError) as error:  # NaN, a YAML date...: JSON cannot carry them
        raise CliError(f"the request cannot be sent as JSON: {error}") from None
    try:
        return request_once("POST", core_url() + path, payload, timeout_s=timeout_s, headers=auth_headers())
    except HttpTimeout:
        raise CliError(f"no answer from {path} within {timeout_s:g} s (--timeout to wait longer)") from None
    except HttpError as error:
        raise _unreachable(error) from None


def unknown_name(kind: str, name: str) -> Callable[[], str]:
    """``get_json``'s ``missing`` for a topic, service or node the system does not have: the one
    line, with the nearest names it has (``unknown topic /x (did you mean /y?): see ...``)."""
    from services.cli.suggestions import graph_names, unknown

    return lambda: unknown(kind, name, graph_names(get_json("/api/graph"), kind + "s"), listing=f"skydeck {kind} list")


def error_detail(reply: HttpReply) -> str:
    """What a refusal says: its ``detail``, and for FastAPI's 422 the first bad field."""
    try:
        body = reply.json()
    except ValueError:
        return reply.text.strip()
    detail = body.get("detail", reply.text) if isinstance(body, dict) else body
    if isinstance(detail, list) and detail and isinstance(detail[0], dict):  # FastAPI's 422
        first = detail[0]
        return f"{'.'.join(str(p) for p in first.get('loc', [])[1:]) or 'body'}: {first.get('msg')}"
    return detail if isinstance(detail, str) else str(detail)
