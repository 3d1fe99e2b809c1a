"""``skydeck bag play``: a node that publishes a recording again, with its timing (rosbag play).

    with BagReader("run.mcap") as bag:
        player = Player(bag, PlayOptions(rate=2.0, clock=True))
        asyncio.run(player.run_until_stopped())    # ends when the recording has been played

Each message is published as recorded, its frame untouched (``publish(frame)``), at its receive
time relative to the first one played, divided by ``rate``. ``clock`` publishes ``/clock`` from
the recording, so nodes with ``use_sim_time`` run on the recording's time: the recording's own
``/clock`` when it has one (the simulator's time, which its headers are stamped in), played even
when ``topics`` leaves it out, else its receive times, at ``clock_hz``. ``pause()`` /
``resume()`` hold the timeline (the space bar does it in a terminal); a paused player publishes
nothing, ``/clock`` included.
"""

from __future__ import annotations

import asyncio
import math
import os
import threading
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from services.bag.cdr import CDR_ENCODING
from services.bag.errors import BagError
from services.bag.reader import BagMessage, BagReader
from services.bag.schemas import MESSAGE_ENCODING, message_type
from services.runtime.node import Node
from services.runtime.publisher import Publisher
from services.runtime.settings import NodeSettings
from shared_models.builtin_interfaces import Time

# The reader hands CDR messages over as JSON frames (services.bag.cdr).
PLAYABLE = (MESSAGE_ENCODING, CDR_ENCODING)

__all__ = ["CLOCK_TOPIC", "PlayOptions", "Player", "check_types"]

CLOCK_TOPIC = "/clock"
_QUEUE_SIZE = 1000
_FINE_S = 0.001  # the last stretch of a wait, slept without being woken (see Player._wait_until)
_IN_FLIGHT = 256  # messages handed to the loop and not yet published, at most


@dataclass(frozen=True)
class PlayOptions:
    """How to play: the flags of ``skydeck bag play``."""

    rate: float = 1.0
    loop: bool = False
    start_offset_s: float = 0.0
    topics: frozenset[str] | None = None
    clock: bool = False
    clock_hz: float = 100.0
    remap: Mapping[str, str] = field(default_factory=dict)
    wait_for_subscribers: bool = False

    def __post_init__(self) -> None:
        if not (math.isfinite(self.rate) and self.rate > 0):
            raise BagError(f"--rate must be a positive number, got {self.rate}")
        if not (math.isfinite(self.start_offset_s) and self.start_offset_s >= 0):
            raise BagError(f"--start-offset must be 0 or more seconds, got {self.start_offset_s}")


def check_types(graph_topics: Iterable[Mapping[str, Any]], played: Mapping[str, str]) -> None:
    """BagError if a topic to publish already has another type in the running system."""
    for topic in graph_topics:
        recorded = played.get(topic["name"])
        if recorded and topic.get("type") and topic["type"] != recorded:
            raise BagError(
                f"{topic['name']} is {topic['type']} in the running system but {recorded} in the recording: "
                "--remap it to another name, or leave it out with --topics"
            )


class Player(Node):
    """Publishes the messages of ``reader`` again; ``played`` counts them."""

    def __init__(
        self,
        reader: BagReader,
        options: PlayOptions = PlayOptions(),
        *,
        settings: NodeSettings | None = None,
        say: Callable[[str], None] = lambda _: None,
    ) -> None:
        summary = reader.summary
        recorded = {topic.topic: topic for topic in summary.topics}
        chosen = sorted(recorded) if options.topics is None else sorted(options.topics)
        unknown = [name for name in chosen if name not in recorded]
        if unknown:
            raise BagError(
                f"{reader.path} has no topic {', '.join(unknown)}; it has: {', '.join(recorded) or 'none'}"
            )
        # --clock plays the recorded /clock even when --topics leaves it out: it is the time
        # the recording's headers are stamped in, which use_sim_time nodes must run on.
        self._clock_added = options.clock and CLOCK_TOPIC in recorded and CLOCK_TOPIC not in chosen
        if self._clock_added:
            chosen.append(CLOCK_TOPIC)
        unknown_remaps = [name for name in options.remap if name not in recorded]
        if unknown_remaps:
            raise BagError(f"--remap names {', '.join(unknown_remaps)}, which {reader.path} does not have")
        if options.start_offset_s > summary.duration_s:
            raise BagError(
                f"--start-offset {options.start_offset_s:g} s is past the end of {reader.path} ({summary.duration_s:.3f} s)"
            )
        for name in chosen:
            if recorded[name].encoding not in PLAYABLE:
                raise BagError(
                    f"{name} is recorded as {recorded[name].encoding!r}: Skydeck plays JSON and CDR (ROS 2) recordings"
                )
        super().__init__(f"bag_play_{os.getpid()}", settings=settings)
        self.reader = reader
        self.options = options
        self.played = 0
        self.lateness_s: list[float] | None = None  # set to a list to collect each message's lateness
        self._say = say
        self.topics = {name: options.remap.get(name, name) for name in chosen}
        if self._clock_added:
            self.topics[CLOCK_TOPIC] = CLOCK_TOPIC
        self._publishers: dict[str, Publisher[Any]] = {}
        for name in chosen:
            msg_type = message_type(recorded[name].type_name)
            self._publishers[name] = self.create_publisher(
                msg_type, self.topics[name], _QUEUE_SIZE, latched=recorded[name].latched
            )
        self._clock_publisher: Publisher[Time] | None = None
        if options.clock and CLOCK_TOPIC not in self.topics.values():
            self._clock_publisher = self.create_publisher(Time, CLOCK_TOPIC, 10)
        # Shared with the timeline thread: what it waits on, and the pause state it reads.
        self._wake = threading.Event()  # a pause, resume or stop: the thread looks again
        self._ending = threading.Event()
        self._in_flight = threading.Semaphore(_IN_FLIGHT)
        self._held: list[tuple[BagMessage, float]] = []  # handed over just as a pause came
        self._paused_s = 0.0  # the pauses so far, in total
        self._paused_at: float | None = None  # when the pause in progress began
        self._base: tuple[int, float] | None = None  # (log time, perf_counter) of the first played
        self._position_ns = summary.start_ns
        self._task: asyncio.Task[None] | None = None

    @property
    def played_types(self) -> dict[str, str]:
        """Published name -> recorded type, for :func:`check_types`."""
        return {
            self.topics[topic.topic]: topic.type_name
            for topic in self.reader.summary.topics
            if topic.topic in self.topics
        }

    # -- pause --------------------------------------------------------------------------------

    @property
    def paused(self) -> bool:
        return self._paused_at is not None

    def pause(self) -> None:
        if self.paused:
            return
        self._paused_at = time.perf_counter()
        self._wake.set()
        self._say(f"[PAUSED]  at {self.position_s:.3f} s of {self.reader.summary.duration_s:.3f} s (space resumes)")

    def resume(self) -> None:
        paused_at = self._paused_at
        if paused_at is None:
            return
        self._paused_s += time.perf_counter() - paused_at  # before paused turns False: the thread reads both
        self._paused_at = None
        self._wake.set()
        self._say(f"[RUNNING] from {self.position_s:.3f} s")
        held, self._held = self._held, []
        for message, due_s in held:
            self._publish(message, due_s)

    def toggle_pause(self) -> None:
        self.resume() if self.paused else self.pause()

    @property
    def position_s(self) -> float:
        """Where playback is, seconds from the start of the recording."""
        return (self._position_ns - self.reader.summary.start_ns) / 1e9

    # -- running ------------------------------------------------------------------------------

    async def start(self) -> None:
        await super().start()
        self._task = asyncio.get_running_loop().create_task(self._play())
        if self._clock_publisher is not None:
            self.create_timer(1.0 / self.options.clock_hz, self._publish_clock, wall_clock=True)

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            await asyncio.gather(self._task, return_exceptions=True)
        await super().stop()

    async def _play(self) -> None:
        try:
            if self.options.wait_for_subscribers:
                await self._wait_for_subscribers()
            timeline = asyncio.ensure_future(asyncio.to_thread(self._timeline, asyncio.get_running_loop()))
            try:
                await asyncio.shield(timeline)
            finally:
                self._ending.set()
                self._wake.set()  # out of _wait_until
                self._in_flight.release()  # out of _in_flight_slot
                await asyncio.shield(timeline)  # the thread reads the file: it ends before the file is closed
        finally:
            self.destroy_node()

    async def _wait_for_subscribers(self) -> None:
        """Wait until each chosen topic has a subscriber (the /clock that --clock added need not)."""
        chosen = {
            name: publisher
            for name, publisher in self._publishers.items()
            if not (self._clock_added and name == CLOCK_TOPIC)
        }
        waiting = [self.topics[name] for name, publisher in chosen.items() if publisher.get_subscription_count() == 0]
        if waiting:
            self._say(f"waiting for a subscriber on {', '.join(waiting)}")
        while any(publisher.get_subscription_count() == 0 for publisher in chosen.values()):
            await asyncio.sleep(0.01)

    # -- the timeline, on its own thread ------------------------------------------------------
    #
    # The event loop is a poor clock: it wakes up to a millisecond late (epoll's timeout is in
    # whole ms) and is late again whenever it is busy with a socket. So a thread keeps the
    # timeline: it reads (and decompresses) each message ahead of its time, sleeps until it is
    # due with the OS's high-resolution timer, and only then hands it to the loop, whose part
    # is just the write (``publish(frame)``). The loop is never blocked by the waiting.

    def _timeline(self, loop: asyncio.AbstractEventLoop) -> None:
        start_ns = self.reader.summary.start_ns + int(self.options.start_offset_s * 1e9)
        while not self._ending.is_set():
            self._timeline_once(loop, start_ns)
            if not self.options.loop:
                break

    def _timeline_once(self, loop: asyncio.AbstractEventLoop, start_ns: int) -> None:
        self._base = None
        scale = 1e-9 / self.options.rate
        publish = self._publish
        for message in self.reader.messages(self._publishers, start_ns=start_ns):
            if self._base is None:
                self._base = (message.log_time_ns, time.perf_counter())
            due_s = self._base[1] + (message.log_time_ns - self._base[0]) * scale
            if not self._wait_until(due_s) or not self._in_flight_slot():
                return
            loop.call_soon_threadsafe(publish, message, due_s)

    def _wait_until(self, due_s: float) -> bool:
        """Sleep until ``due_s`` on the playback timeline (it stands still while paused); False
        if the player is stopping. Woken early by pause, resume and stop."""
        while True:
            self._wake.clear()  # before looking: a pause, resume or stop from here on ends the wait below
            if self._ending.is_set():
                return False
            if self.paused:
                self._wake.wait()
                continue
            delay_s = due_s + self._paused_s - time.perf_counter()
            if delay_s <= 0:
                return True
            if delay_s > _FINE_S:
                self._wake.wait(delay_s - _FINE_S)
            else:
                time.sleep(delay_s)  # clock_nanosleep: within ~0.1 ms when the thread is scheduled

    def _in_flight_slot(self) -> bool:
        """Wait until the loop has room for one more message (a burst never piles up in it);
        False if the player is stopping."""
        self._in_flight.acquire()
        return not self._ending.is_set()

    def _publish(self, message: BagMessage, due_s: float) -> None:
        """On the loop: the write of one message that is due (held if paused meanwhile)."""
        if self.paused:
            self._held.append((message, due_s))  # keeps its in-flight slot until published
            return
        self._in_flight.release()
        self._publishers[message.topic].publish(message.frame)
        if self.lateness_s is not None:
            self.lateness_s.append(time.perf_counter() - due_s - self._paused_s)
        self._position_ns = message.log_time_ns
        self.played += 1

    def _publish_clock(self) -> None:
        if self.paused or self._base is None or self._clock_publisher is None:
            return
        elapsed_s = time.perf_counter() - self._base[1] - self._paused_s
        now_ns = self._base[0] + int(elapsed_s * self.options.rate * 1e9)
        sec, nanosec = divmod(max(now_ns, self._position_ns), 1_000_000_000)
        self._clock_publisher.publish(Time(sec=sec, nanosec=nanosec))
