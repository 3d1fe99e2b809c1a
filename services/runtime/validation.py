"""FastAPI's 422 for bad bodies, made safe for any input (NaN and infinity included).

FastAPI echoes the offending ``input`` back; when that is a non-finite float, or a body of
bytes that are not UTF-8, the default handler cannot encode it and answers 500. Here the detail
keeps FastAPI's shape, with non-finite numbers written as strings and undecodable bytes
replaced (U+FFFD).
"""

from __future__ import annotations

import math
from typing import Any

from fastapi import Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

__all__ = ["request_validation_handler"]


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
