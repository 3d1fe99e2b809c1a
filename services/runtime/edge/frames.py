"""Frames refused with a close code and a reason that names the field; whether a frame named
every field; and closing a socket with a reason that fits a close frame. (Validating a frame of
either encoding against its type: :func:`services.runtime.edge.encoding.decode`.)"""

from __future__ import annotations

import contextlib

from pydantic import ValidationError
from starlette.websockets import WebSocket, WebSocketState

from shared_models import Message
from shared_models.errors import SkydeckError

__all__ = ["FrameRejected", "close_with", "describe_validation_error", "is_complete"]

_MAX_REASON_BYTES = 123  # RFC 6455: a close frame's reason fits in 123 bytes


class FrameRejected(SkydeckError):
    """A frame or option a client sent cannot be taken; closes that socket with ``code``."""

    http_status = 400

    def __init__(self, code: int, reason: str) -> None:
        super().__init__(reason)
        self.code = code
        self.reason = reason

    @property
    def close_code(self) -> int:  # type: ignore[override]
        return self.code


def describe_validation_error(type_name: str, error: ValidationError) -> str:
    """One line naming the first bad field of a frame: ``invalid geometry_msgs/msg/Twist: ...``."""
    first = error.errors(include_url=False)[0]
    location = ".".join(str(part) for part in first["loc"]) or "(message)"
    more = f" (+{error.error_count() - 1} more)" if error.error_count() > 1 else ""
    return f"invalid {type_name}: {location}: {first['msg']}{more}"


def is_complete(msg: Message) -> bool:
    """Whether the frame ``msg`` was parsed from named every field, at every depth.

    Such a frame can be forwarded as it came: every reader, including those that do not know
    the type's defaults (a browser), gets the whole message. Checking is far cheaper than
    serialising again, most of all for big messages (an image's base64 is not looked at).
    """
    if len(msg.model_fields_set) != len(type(msg).model_fields):
        return False
    for name in type(msg).model_fields:
        value = getattr(msg, name)
        if isinstance(value, Message) and not is_complete(value):
            return False
        if (
            isinstance(value, list)
            and value
            and isinstance(value[0], Message)
            and not all(is_complete(item) for item in value)
        ):
            return False
    return True


def _clip_reason(reason: str) -> str:
    data = reason.encode()
    if len(data) <= _MAX_REASON_BYTES:
        return reason
    return data[: _MAX_REASON_BYTES - 3].decode(errors="ignore") + "..."


async def close_with(websocket: WebSocket, code: int, reason: str) -> None:
    """Close ``websocket`` with ``code`` and a reason clipped to what a close frame can carry."""
    if websocket.application_state == WebSocketState.DISCONNECTED:
        return
    with contextlib.suppress(RuntimeError, OSError):
        await websocket.close(code=code, reason=_clip_reason(reason))
