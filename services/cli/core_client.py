"""Talking to the core from the CLI: its URL, JSON requests, and readable errors."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from services.cli.errors import CliError
from services.cli.settings import cli_settings

if TYPE_CHECKING:
    import httpx

__all__ = ["auth_headers", "core_url", "error_detail", "get_json", "node_settings", "post_json", "unknown_name", "ws_url"]


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
        f"cannot reach the core at {core_url()} ({type(error).__name__}): is it running? "
        "start it with `skydeck core` (or `make up`), or set SKYDECK_CORE_URL"
    )


def get_json(path: str, *, missing: str | Callable[[], str] | None = None) -> Any:
    """GET ``path`` on the core; a 404 raises CliError(``missing``) when given (a callable is
    asked only then: what to say may take another request, as the nearest names do)."""
    import httpx  # here, not at the top: `skydeck launch` runs all session without it

    try:
        reply = httpx.get(core_url() + path, headers=auth_headers(), timeout=5.0)
    except httpx.HTTPError as error:
        raise _unreachable(error) from None
    if reply.status_code == 404 and missing is not None:
        raise CliError(missing if isinstance(missing, str) else missing())
    if reply.status_code != 200:
        raise CliError(f"the core answered {reply.status_code} for {path}: {error_detail(reply)}")
    return reply.json()


def post_json(path: str, body: Any, *, timeout_s: float) -> httpx.Response:
    """POST ``body`` as JSON to ``path`` on the core and return the reply, whatever its status."""
    import httpx

    try:
        return httpx.post(core_url() + path, json=body, headers=auth_headers(), timeout=timeout_s)
    except httpx.TimeoutException:
        raise CliError(f"no answer from {path} within {timeout_s:g} s (--timeout to wait longer)") from None
    except httpx.HTTPError as error:
        raise _unreachable(error) from None


def unknown_name(kind: str, name: str) -> Callable[[], str]:
    """``get_json``'s ``missing`` for a topic, service or node the system does not have: the one
    line, with the nearest names it has (``unknown topic /x (did you mean /y?): see ...``)."""
    from services.cli.suggestions import graph_names, unknown

    return lambda: unknown(kind, name, graph_names(get_json("/api/graph"), kind + "s"), listing=f"skydeck {kind} list")


def error_detail(reply: httpx.Response) -> str:
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
