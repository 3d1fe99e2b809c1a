"""What a protocol endpoint's connection does with the core, in one place for every protocol.

An adapter (rosbridge, Foxglove) translates its frames into these calls and nothing else:

- ``start_reading(topic, ...)``: an :class:`Outbox` opened on the topic's
  :class:`~services.core.gateway_topic.GatewayTopic`, written to the socket by the edge's own
  writer (``write_outbox``) in the protocol's form (``encode``);
- ``publish(topic, text)``: the same validation, fences and "no echo" as a native socket (back to
  its own readings only with ``echo``);
- ``call(service, body)``: the one service-call path of the HTTP gateway;
- ``visitor``: who the connection's token is and what it may do (:mod:`services.access`), checked
  by the topic views and the call path; ``authenticate(token)`` for a token sent later;
- ``guest``: the connection as the graph shows it (``/rosbridge_client_3``);
- ``serve(frames)``: the adapter's frame loop, beside the stall watch a native reader has.

A refusal of the fences is an :class:`~services.access.AccessRefused` (a SkydeckError) that the
adapter answers in its own way, for that op alone. A student's connection that publishes more
than their rate allows is shed: ``serve`` returns the reason (close 4002) as for a stall.

Each topic a connection reads has its own bounded outbox and writer, so a client that falls
behind loses its own oldest frames; one that stops reading altogether (a send has waited for
its socket for ``SKYDECK_STALL_TIMEOUT_S``) is detached and closed with 4001, like a stalled
native reader (docs/streams.md). The publishers and every other client go on meanwhile.

A connection reads each topic once, however many subscriptions its client makes to it (the
adapter merges them). Whether what it publishes on a topic it reads comes back to it is the
protocol's (``echo``): a native socket never gets its own frames back, a rosbridge connection
does, as ROS delivers a node's own messages to its subscriptions (docs/protocols.md).
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncIterator, Coroutine
from dataclasses import dataclass, field
from typing import Any

from starlette.websockets import WebSocket, WebSocketDisconnect

from services.access import Pass, RateLimited, Role, Verb
from services.core.access import CoreAccess
from services.core.gateway_topic import GatewayTopic
from services.core.guests import Guest
from services.core.service_calls import ServiceReply
from services.protocols.ops import Refused
from services.runtime.auth import presented_token
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.outbox import Outbox
from services.runtime.edge.pump import Encode, watch_stall, write_outbox
from shared_models import Message

__all__ = ["ClientSession", "Reading", "incoming"]


async def incoming(websocket: WebSocket, max_bytes: int) -> AsyncIterator[str | bytes | None]:
    """Each frame the client sends (text as ``str``, binary as ``bytes``) until it goes away;
    ``None`` stands for a frame over ``max_bytes``, which the adapter answers in its own way."""
    while True:
        try:
            message = await websocket.receive()
        except (WebSocketDisconnect, RuntimeError):
            return
        if message["type"] == "websocket.disconnect":
            return
        text: str | None = message.get("text")
        if text is None:
            data: bytes = message.get("bytes") or b""
            yield data if len(data) <= max_bytes else None
        else:  # UTF-8 takes at most 4 bytes a character: encode only when that could matter
            too_big = len(text) > max_bytes or (len(text) * 4 > max_bytes and len(text.encode()) > max_bytes)
            yield None if too_big else text


@dataclass(eq=False)
class Reading:
    """One topic a connection reads: its outbox, and the task writing it to the socket."""

    topic: GatewayTopic
    outbox: Outbox
    task: asyncio.Task[None] | None = field(default=None, repr=False)


class ClientSession:
    """One protocol connection's readings, publications and calls (see the module docstring)."""

    @classmethod
    def open(cls, access: CoreAccess, websocket: WebSocket, protocol: str, *, echo: bool = False) -> ClientSession:
        """A new connection of ``protocol`` ("rosbridge", "foxglove"), shown in the graph as
        ``/PROTOCOL_client_N``; with ``echo``, what it publishes comes back to its own readings."""
        peer = f"{websocket.client.host}:{websocket.client.port}" if websocket.client else "?"
        guest = access.guests.add(f"/{protocol}_client", client=f"{protocol} client {peer}", numbered=True)
        return cls(access, websocket, guest, echo=echo)

    def __init__(self, access: CoreAccess, websocket: WebSocket, guest: Guest, *, echo: bool = False) -> None:
        self.access = access
        self.guest = guest
        self.visitor: Pass = access.fences.admit(presented_token(websocket))
        self.echo = echo
        self._send = websocket.send
        self.readings: dict[str, Reading] = {}
        self._publications: dict[str, GatewayTopic] = {}
        self._replies_waiting: list[float] = []  # since when each reply being sent has waited
        self._shed: asyncio.Future[FrameRejected] = asyncio.get_running_loop().create_future()

    async def serve(self, frames: Coroutine[Any, Any, None], *, advice: str) -> FrameRejected | None:
        """Run the adapter's frame loop ``frames`` until the client leaves; or, if the client
        stops reading, end it and return the reason to close with (4001): the caller detaches
        the connection (``close``), then closes the socket with it, as for a native reader.
        ``advice`` ends that reason: what the client can do instead."""
        loop = asyncio.get_running_loop()
        reading = loop.create_task(frames)
        watching = loop.create_task(
            watch_stall(self._waiting_since, self._dropped, self.access.settings.reader_stall_s, advice)
        )
        try:
            done, _ = await asyncio.wait((reading, watching, self._shed), return_when=asyncio.FIRST_COMPLETED)
        finally:
            reading.cancel()
            watching.cancel()
        if self._shed in done:
            return self._shed.result()
        if reading in done:
            reading.result()  # an adapter's own error is raised, not hidden
            return None
        stalled = watching.exception()
        if isinstance(stalled, FrameRejected):
            return stalled
        raise stalled or RuntimeError("the stall watch ended")

    def _waiting_since(self) -> float | None:
        waiting = [r.outbox.busy_since for r in self.readings.values() if r.outbox.busy_since is not None]
        return min(waiting + self._replies_waiting, default=None)

    def _dropped(self) -> int:
        return sum(reading.outbox.dropped for reading in self.readings.values())

    def authenticate(self, token: str) -> None:
        """The client presents ``token`` now (rosbridge's ``auth``): from here on the connection
        acts as its subject. Refused for a token nobody has."""
        visitor = self.access.fences.admit(token)
        if visitor.subject.role is Role.ANONYMOUS and not visitor.unlimited:
            raise Refused(
                "auth: the mac is not this core's token (SKYDECK_TOKEN), nor rosauth's MAC made with it in time, "
                "nor a class token"
            )
        self.visitor = visitor

    # -- reading --------------------------------------------------------------------------------

    def start_reading(
        self,
        topic: str,
        *,
        queue: int,
        rate_hz: float | None = None,
        paced_queue: bool = False,
        encode: Encode | None = None,
        for_client: bool = True,
    ) -> Reading:
        """Send ``topic``'s frames to this socket (replacing an earlier reading of it).

        ``queue`` frames may wait before the oldest is dropped; with ``rate_hz``, one frame is
        sent at most that often: the newest (the queue holds one), or with ``paced_queue`` the
        oldest of ``queue``. A latched topic's latest frame goes first. AccessRefused if the
        client may not read it; ``for_client=False`` reads for the adapter itself (Foxglove's
        clock, parameter events it filters), unfenced.
        """
        view = GatewayTopic(
            self.access.core, self.access.registry, topic, None, visitor=self.visitor if for_client else None
        )
        view.check(Verb.READ)  # before the reading it replaces stops: a refusal changes nothing
        self.stop_reading(topic)
        outbox = Outbox(1 if rate_hz and not paced_queue else max(1, queue))
        reading = Reading(view, outbox)
        latched = view.start_reading(outbox)
        reading.task = asyncio.get_running_loop().create_task(
            write_outbox(self._send, outbox, rate_hz=rate_hz, paced_queue=paced_queue, initial_frame=latched, encode=encode)
        )
        self.readings[topic] = reading
        self.guest.reads(topic)
        return reading

    def stop_reading(self, topic: str) -> None:
        reading = self.readings.pop(topic, None)
        if reading is None:
            return
        reading.topic.stop_reading(reading.outbox)
        if reading.task is not None:
            reading.task.cancel()
        self.guest.stops_reading(topic)

    # -- publishing -----------------------------------------------------------------------------

    def declare(self, topic: str, declared: type[Message] | None, *, latched: bool = True) -> GatewayTopic:
        """This connection publishes ``topic`` (of type ``declared``, if the client names one),
        from now on: the core advertises it, so subscribers link before the first frame. With
        ``latched``, its latest message goes to subscribers that come later.

        Raises FrameRejected(1008) when the type is missing for a new topic or differs from the
        topic's, AccessRefused when the client may not publish it.
        """
        view = self._publications.get(topic)
        if view is not None and declared in (None, view.message_type()) and view.latched == latched:
            return view
        view = GatewayTopic(
            self.access.core, self.access.registry, topic, declared, visitor=self.visitor, latched=latched
        )
        view.check(Verb.PUBLISH)
        view.message_type()  # refuses a type that does not fit before anything is published
        self.stop_publishing(topic)
        view.advertise()
        self._publications[topic] = view
        self.guest.publishes(topic, view.message_type().__ros_type__)
        return view

    def publication(self, topic: str) -> GatewayTopic | None:
        """This connection's publication of ``topic``, if it publishes it."""
        return self._publications.get(topic)

    def publish(self, topic: str, text: str, *, latched: bool = True) -> None:
        """Validate and publish one frame on ``topic``, to everyone (this connection too, with
        ``echo``); the first frame of a topic not declared yet declares it (``latched``).

        Raises FrameRejected (1008 without a type, 1007 for a frame of another type),
        AccessRefused (the client may not publish it). A frame over the subject's rate is
        dropped and the connection shed (``serve`` returns the reason, 4002).
        """
        view = self._publications.get(topic) or self.declare(topic, None, latched=latched)
        reading = None if self.echo else self.readings.get(topic)
        try:
            view.publish(text, reading.outbox if reading is not None else None)
        except RateLimited as limited:
            if not self._shed.done():
                self._shed.set_result(FrameRejected(limited.close_code, str(limited)))

    def stop_publishing(self, topic: str) -> bool:
        """This connection publishes ``topic`` no more; False if it did not."""
        view = self._publications.pop(topic, None)
        if view is None:
            return False
        view.stop_publishing()
        self.guest.stops_publishing(topic)
        return True

    # -- services -------------------------------------------------------------------------------

    async def call(self, service: str, body: bytes, *, timeout_s: float | None = None) -> ServiceReply:
        """Call ``service`` through the gateway's one call path (raises ServiceCallFailed)."""
        return await self.access.calls.call(service, body, caller=self.visitor, timeout_s=timeout_s)

    # -- the end --------------------------------------------------------------------------------

    def close(self) -> None:
        """Stop every reading and publication and leave the graph."""
        for topic in list(self.readings):
            self.stop_reading(topic)
        for topic in list(self._publications):
            self.stop_publishing(topic)
        for name in list(self.guest.services):
            self.guest.stops_serving(name)
        self.access.guests.remove(self.guest)

    async def send_text(self, text: str) -> None:
        """Send one protocol message of this connection's own (a reply, a status)."""
        await self._reply({"type": "websocket.send", "text": text})

    async def send_bytes(self, data: bytes) -> None:
        await self._reply({"type": "websocket.send", "bytes": data})

    async def _reply(self, message: dict[str, Any]) -> None:
        started = time.monotonic()
        self._replies_waiting.append(started)  # the stall watch sees a reply that cannot go out
        try:
            with contextlib.suppress(RuntimeError, OSError):
                await self._send(message)
        finally:
            self._replies_waiting.remove(started)
