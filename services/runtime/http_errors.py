"""How errors become HTTP answers, in one place for the core and every node.

- A :class:`~shared_models.errors.SkydeckError` that reaches a route answers its
  ``http_status`` with ``{"detail": message}`` (the message says what to do).
- FastAPI's 422 for bad bodies, made safe for any input (NaN and infinity included): FastAPI echoes the offending ``input`` back; when that is a non-finite float, or a body of
bytes that are not UTF-8, the default handler cannot encode it and answers 500. Here the detail
keeps FastAPI's shape, with non-finite numbers written as strings and undecodable bytes
replaced (U+FFFD).
"""

from __future__ import annotations

import math
from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

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


async def skydeck_error_handler(request: Request, error: Exception) -> JSONResponse:
    """A SkydeckError's own status, with its message as the detail."""
    status = error.http_status if isinstance(error, SkydeckError) else 500
    return JSONResponse({"detail": str(error)}, status_code=status)


def install_error_handlers(app: FastAPI) -> None:
    """Map Skydeck's errors and bad bodies to HTTP answers on ``app``."""
    app.add_exception_handler(RequestValidationError, request_validation_handler)
    app.add_exception_handler(SkydeckError, skydeck_error_handler)
