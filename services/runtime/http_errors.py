"""How errors become HTTP answers, in one place for the core and every node.

- A :class:`~shared_models.errors.SkydeckError` that reaches a route answers its
  ``http_status`` with ``{"detail": message}`` (the message says what to do).
- FastAPI's 422 for bad bodies, made safe for any input (NaN and infinity included): FastAPI echoes the offending ``input`` back; when that is a non-finite float, or a body of
bytes that are not UTF-8, the default handler cannot encode it and answers 500. Here the detail
keeps FastAPI's shape, with non-finite numbers written as strings and undecodable bytes
replaced (U+FFFD). A body FastAPI cannot even decode (bytes that are not UTF-8) is a bad body
too: 422, where FastAPI would answer an undocumented 400.
"""

from __future__ import annotations

import math
from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exception_handlers import http_exception_handler
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response
from starlette.exceptions import HTTPException

from shared_models.errors import SkydeckError

__all__ = ["install_error_handlers", "request_validation_handler"]


def _json_safe(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, bytes | bytearray):
        return bytes(value).decode(errors="replace")
    if isinstance(value, dict):
        return {key: _json_safe(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(item) for item in value]
    return value


async def request_validation_handler(request: Request, error: Exception) -> JSONResponse:
    """422 with FastAPI's usual ``{"detail": [...]}`` body."""
    errors = error.errors() if isinstance(error, RequestValidationError) else []
    return JSONResponse({"detail": _json_safe(jsonable_encoder(_json_safe(errors)))}, status_code=422)


# FastAPI's own answer when a body cannot be decoded at all (fastapi/routing.py).
_UNPARSEABLE_BODY = "There was an error parsing the body"


async def undecodable_body_handler(request: Request, error: Exception) -> Response:
    """422 for a body FastAPI could not decode (its 400), as for any other bad body."""
    if isinstance(error, HTTPException) and error.status_code == 400 and error.detail == _UNPARSEABLE_BODY:
        detail = [{"type": "json_invalid", "loc": ["body"], "msg": "the body is not UTF-8 JSON", "input": None}]
        return JSONResponse({"detail": detail}, status_code=422)
    return await http_exception_handler(request, error)  # type: ignore[arg-type]


async def skydeck_error_handler(request: Request, error: Exception) -> JSONResponse:
    """A SkydeckError's own status, with its message as the detail."""
    status = error.http_status if isinstance(error, SkydeckError) else 500
    return JSONResponse({"detail": str(error)}, status_code=status)


def install_error_handlers(app: FastAPI) -> None:
    """Map Skydeck's errors and bad bodies to HTTP answers on ``app``."""
    app.add_exception_handler(RequestValidationError, request_validation_handler)
    app.add_exception_handler(HTTPException, undecodable_body_handler)
    app.add_exception_handler(SkydeckError, skydeck_error_handler)
