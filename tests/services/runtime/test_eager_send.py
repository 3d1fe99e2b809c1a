"""The eager send of a frame from publish() while the writer is idle (unit level: a fake ASGI
send in place of the socket)."""

from __future__ import annotations

import asyncio

import pytest

from services.runtime.edge.outbox import Outbox
from services.runtime.edge.pump import _EagerSend, _messages

pytestmark = pytest.mark.timeout(10)


class FakeSocket:
    """An ASGI send that writes at once, or waits while ``writable`` is clear."""

    def __init__(self) -> None:
        self.written: list[str] = []
        self.writable = asyncio.Event()
        self.writable.set()
        self.broken = False

    async def send(self, message: dict[str, str]) -> None:
        await self.writable.wait()
        if self.broken:
            raise OSError("connection lost")
        self.written.append(message["text"])


async def test_a_send_that_does_not_wait_is_done_inside_the_call() -> None:
    socket = FakeSocket()
    eager = _EagerSend(socket.send, Outbox(10), _messages)
    assert eager("a") and eager("b")
    assert socket.written == ["a", "b"]  # no turn of the event loop in between
    await eager.settled()


async def test_a_send_that_must_wait_finishes_later_and_later_frames_queue_behind_it() -> None:
    socket = FakeSocket()
    socket.writable.clear()  # the transport paused writing
    eager = _EagerSend(socket.send, Outbox(10), _messages)
    assert eager("a")  # taken: it will be written when the socket drains
    assert not eager("b")  # declined: the writer queues it behind "a"
    assert socket.written == []
    socket.writable.set()
    await asyncio.wait_for(eager.settled(), 5)
    assert socket.written == ["a"]
    assert eager("c") and socket.written == ["a", "c"]


async def test_a_broken_socket_declines_so_the_writer_meets_the_error() -> None:
    socket = FakeSocket()
    socket.broken = True
    eager = _EagerSend(socket.send, Outbox(10), _messages)
    assert not eager("a")


async def test_an_error_after_waiting_is_raised_by_settled() -> None:
    socket = FakeSocket()
    socket.writable.clear()
    eager = _EagerSend(socket.send, Outbox(10), _messages)
    assert eager("a")
    socket.broken = True
    socket.writable.set()
    with pytest.raises(OSError, match="connection lost"):
        await asyncio.wait_for(eager.settled(), 5)


async def test_cancel_stops_a_waiting_send() -> None:
    socket = FakeSocket()
    socket.writable.clear()
    eager = _EagerSend(socket.send, Outbox(10), _messages)
    assert eager("a")
    eager.cancel()
    await asyncio.sleep(0)
    socket.writable.set()
    await asyncio.sleep(0.01)
    assert socket.written == []
