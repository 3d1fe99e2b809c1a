"""Calling user callbacks, which may be plain functions or coroutines."""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable
from typing import Any

__all__ = ["call_user"]


async def call_user(callback: Callable[..., Any], *args: Any, logger: logging.Logger, what: str) -> Any:
    """Call ``callback(*args)``, awaiting it if it returns an awaitable.

    An exception in user code is logged with its traceback and swallowed, so one bad message
    does not stop the node; ``None`` is returned in that case.
    """
    try:
        result = callback(*args)
        if inspect.isawaitable(result):
            result = await result
        return result
    except Exception:
        logger.exception("%s raised; the node keeps running", what)
        return None
