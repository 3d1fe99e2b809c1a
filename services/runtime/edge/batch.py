"""Several messages in one frame, for readers that ask for it (``?batch=1``): how nodes link.

A frame normally holds one message: a msgpack map, or a JSON object. A reader that asks for
batches may also get a frame holding several, oldest first: the messages a publisher had for it
at once (those published in one turn of its event loop, or queued while its socket was busy).

- msgpack: a msgpack *array* of the messages (a lone message is never an array);
- JSON text: the messages one per line (JSON Lines). Outside strings a newline in JSON is only
  whitespace and inside strings it is always escaped, so a batching reader is sent its
  messages with any newline made a space, and a newline in a frame then only ever separates two.

Joining copies bytes and serialises nothing again. It saves a reader what each frame costs
apart from its message (the WebSocket parsing, a hand-over per frame).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import ormsgpack

from services.runtime.edge.frames import FrameRejected
from services.runtime.wire import Close

__all__ = ["BATCH_MAX_BYTES", "is_batch", "join", "one_line", "split"]

BATCH_MAX_BYTES = 64 << 10
"""A batch grows to at most this many bytes; a bigger message goes alone, as it would anyway."""

Frame = str | bytes

_FIXARRAY, _ARRAY16, _ARRAY32 = 0x90, 0xDC, 0xDD


def one_line(frame: Frame) -> Frame:
    """A JSON frame as a batching reader is sent it: on one line (a msgpack frame as it is)."""
    if isinstance(frame, str) and "\n" in frame:
        return frame.replace("\n", " ")
    return frame


def join(frames: Sequence[Frame]) -> list[Frame]:
    """``frames`` (oldest first, all of one encoding, JSON ones on one line) as few frames as fit
    in BATCH_MAX_BYTES each. A lone message stays as it is: only two or more are joined."""
    joined: list[Frame] = []
    start, size = 0, 0
    for index, frame in enumerate(frames):
        if size and size + len(frame) > BATCH_MAX_BYTES:
            joined.append(_one(frames[start:index]))
            start, size = index, 0
        size += len(frame)
    if start < len(frames):
        joined.append(_one(frames[start:]))
    return joined


def _one(frames: Sequence[Frame]) -> Frame:
    if len(frames) == 1:
        return frames[0]
    if isinstance(frames[0], str):
        return "\n".join(frames)  # type: ignore[arg-type]
    return _array_header(len(frames)) + b"".join(frames)  # type: ignore[arg-type]


def _array_header(count: int) -> bytes:
    if count < 16:
        return bytes((_FIXARRAY | count,))
    if count < 1 << 16:
        return bytes((_ARRAY16,)) + count.to_bytes(2, "big")
    return bytes((_ARRAY32,)) + count.to_bytes(4, "big")


def is_batch(frame: Frame) -> bool:
    """Whether a frame sent to a batching reader holds several messages."""
    if isinstance(frame, str):
        return "\n" in frame
    if not frame:
        return False
    first = frame[0]
    return first >> 4 == _FIXARRAY >> 4 or first in (_ARRAY16, _ARRAY32)


def split(frame: Frame) -> list[Any]:
    """The messages of a batch: JSON texts, or msgpack values unpacked (neither validated yet);
    FrameRejected(1007) for a msgpack frame that is not an array."""
    if isinstance(frame, str):
        return frame.split("\n")
    try:
        items = ormsgpack.unpackb(frame)
    except (ormsgpack.MsgpackDecodeError, ValueError, TypeError) as error:
        raise FrameRejected(Close.INVALID_FRAME, f"not a msgpack batch: {error}") from None
    if not isinstance(items, list):
        raise FrameRejected(Close.INVALID_FRAME, "not a msgpack batch: not an array")
    return items
