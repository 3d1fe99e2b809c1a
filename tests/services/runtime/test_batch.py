"""Several messages in one frame (``?batch=1``): joining and splitting, the outbox that joins
what one loop turn published, and batching readers and links on real sockets."""

from __future__ import annotations

import asyncio
import json
import logging

import ormsgpack
import pytest
from websockets.asyncio.client import connect

from services.runtime import Node
from services.runtime.edge import batch
from services.runtime.edge.encoding import Encoding, encode
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.links import stream_url
from services.runtime.edge.outbox import Outbox
from shared_models.geometry_msgs import Twist
from tests.conftest import wait_until

pytestmark = pytest.mark.timeout(30)


def _twist(x: float) -> Twist:
    return Twist(linear={"x": x})


# -- joining and splitting --------------------------------------------------------------------


@pytest.mark.parametrize("count", [2, 15, 16, 300])  # fixarray, and array16 from 16 on
def test_msgpack_frames_join_into_an_array_that_splits_back(count: int) -> None:
    frames = [encode(_twist(float(i)), Encoding.MSGPACK) for i in range(count)]
    (joined,) = batch.join(frames)
    assert batch.is_batch(joined)
    assert batch.split(joined) == [ormsgpack.unpackb(frame) for frame in frames]


def test_json_frames_join_into_lines_that_split_back() -> None:
    frames = [_twist(float(i)).model_dump_json() for i in range(5)]
    (joined,) = batch.join(frames)
    assert batch.is_batch(joined)
    assert batch.split(joined) == frames


@pytest.mark.parametrize("encoding", list(Encoding))
def test_a_lone_message_is_not_a_batch(encoding: Encoding) -> None:
    frame = encode(_twist(1.0), encoding)
    assert batch.join([frame]) == [frame]
    assert not batch.is_batch(frame)


def test_a_batch_stops_growing_at_its_byte_limit_and_a_big_message_goes_alone() -> None:
    small = encode(_twist(1.0), Encoding.MSGPACK)
    big = b"\x81\xa1d\xc6" + (batch.BATCH_MAX_BYTES).to_bytes(4, "big") + bytes(batch.BATCH_MAX_BYTES)
    frames = [small] * 3 + [big] + [small] * 2
    joined = batch.join(frames)
    assert joined[1] is big and len(joined) == 3
    assert [len(batch.split(j)) if batch.is_batch(j) else 1 for j in joined] == [3, 1, 2]
    many = [small] * (2 * batch.BATCH_MAX_BYTES // len(small))
    assert all(len(j) <= batch.BATCH_MAX_BYTES + 3 for j in batch.join(many))
    assert sum(len(batch.split(j)) for j in batch.join(many)) == len(many)


def test_a_json_frame_is_put_on_one_line_without_changing_its_meaning() -> None:
    pretty = json.dumps({"linear": {"x": 1.0, "y": 2.0}, "angular": {"z": 3.0}}, indent=2)
    flat = batch.one_line(pretty)
    assert "\n" not in flat and json.loads(flat) == json.loads(pretty)
    packed = encode(_twist(1.0), Encoding.MSGPACK)
    assert batch.one_line(packed) is packed


@pytest.mark.parametrize("frame", [b"\x92\x81", b"\x93\xc1\xc1\xc1"])
def test_a_malformed_msgpack_batch_is_refused_with_1007(frame: bytes) -> None:
    with pytest.raises(FrameRejected) as refused:
        batch.split(frame)
    assert refused.value.code == 1007 and "batch" in refused.value.reason


# -- the outbox -------------------------------------------------------------------------------


async def test_a_batching_outbox_sends_a_turns_first_frame_at_once_and_joins_the_rest() -> None:
    outbox = Outbox(100, Encoding.MSGPACK, batch=True)
    sent: list[bytes] = []
    outbox.send_now = lambda frame: sent.append(frame) is None  # type: ignore[assignment,func-returns-value]
    frames = [encode(_twist(float(i)), Encoding.MSGPACK) for i in range(10)]
    for frame in frames:
        outbox.push(frame)
    assert sent == [frames[0]]  # at once, as an unbatched reader gets it
    await asyncio.sleep(0)  # the end of the loop turn
    assert len(sent) == 2 and batch.split(sent[1]) == [ormsgpack.unpackb(f) for f in frames[1:]]
    await asyncio.sleep(0)
    outbox.push(frames[0])  # a new turn: its first frame goes at once again
    assert sent[2] == frames[0]


async def test_a_batching_outbox_keeps_its_queue_bound_and_the_writer_gets_the_rest_joined() -> None:
    outbox = Outbox(5, Encoding.JSON, batch=True)  # no writer idle: nothing can be sent from push
    for i in range(8):
        outbox.push(_twist(float(i)).model_dump_json(indent=1))
    assert outbox.dropped == 3
    (joined,) = await asyncio.wait_for(outbox.drain(), 5)
    assert [json.loads(line)["linear"]["x"] for line in batch.split(joined)] == [3.0, 4.0, 5.0, 6.0, 7.0]


async def test_a_turn_that_fills_the_queue_sends_a_full_batch_rather_than_dropping() -> None:
    outbox = Outbox(5, Encoding.MSGPACK, batch=True)
    sent: list[bytes] = []
    outbox.send_now = lambda frame: sent.append(frame) is None  # type: ignore[assignment,func-returns-value]
    frames = [encode(_twist(float(i)), Encoding.MSGPACK) for i in range(12)]
    for frame in frames:  # one turn, more than the queue holds, the writer idle
        outbox.push(frame)
    await asyncio.sleep(0)
    assert outbox.dropped == 0
    received = [m for f in sent for m in (batch.split(f) if batch.is_batch(f) else [ormsgpack.unpackb(f)])]
    assert received == [ormsgpack.unpackb(f) for f in frames]


# -- on real sockets --------------------------------------------------------------------------


class Talker(Node):
    def __init__(self, settings) -> None:
        super().__init__("batch_talker", settings=settings)
        self.publisher = self.create_publisher(Twist, "/burst", 1000)

    def burst(self, count: int) -> None:
        for i in range(count):  # one turn of the event loop
            self.publisher.publish(_twist(float(i)))


class Listener(Node):
    def __init__(self, settings) -> None:
        super().__init__("batch_listener", settings=settings)
        self.received: list[float] = []
        self.create_subscription(Twist, "/burst", lambda msg: self.received.append(msg.linear.x), 1000)


async def _read(websocket, count: int, parse) -> tuple[list[float], int]:  # type: ignore[no-untyped-def]
    values: list[float] = []
    frames = 0
    while len(values) < count:
        frame = await asyncio.wait_for(websocket.recv(), 5)
        frames += 1
        values += [parse(message) for message in (batch.split(frame) if batch.is_batch(frame) else [frame])]
    return values, frames


async def test_batching_readers_get_every_message_in_order_in_fewer_frames(start_node) -> None:
    talker = await start_node(Talker)
    count = 200

    def packed_x(message: object) -> float:
        value = ormsgpack.unpackb(message) if isinstance(message, bytes) else message
        return value["linear"]["x"]  # type: ignore[index,no-any-return]

    async with (
        connect(stream_url(talker.url, "/burst", queue=count, encoding="msgpack", batch=1)) as packed,
        connect(stream_url(talker.url, "/burst", queue=count, batch=1)) as text,
        connect(stream_url(talker.url, "/burst", queue=count)) as plain,
    ):
        await wait_until(lambda: len(talker._participant.endpoints["/burst"].outboxes) == 3, what="three readers")
        talker.burst(count)
        expected = [float(i) for i in range(count)]
        packed_values, packed_frames = await _read(packed, count, packed_x)
        text_values, text_frames = await _read(text, count, lambda line: json.loads(line)["linear"]["x"])
        plain_values, plain_frames = await _read(plain, count, lambda frame: json.loads(frame)["linear"]["x"])
    assert packed_values == text_values == plain_values == expected
    assert plain_frames == count
    assert packed_frames < count / 10 and text_frames < count / 10


async def test_a_malformed_batch_from_a_link_is_dropped_with_a_warning_and_the_next_one_delivered(
    start_node, caplog
) -> None:
    listener = await start_node(Listener)
    endpoint = listener._participant.endpoints["/burst"]
    with caplog.at_level(logging.WARNING, logger="skydeck.runtime"):
        endpoint.receive_link_frame(b"\x92\xc1")
        endpoint.receive_link_frame(batch.join([encode(_twist(7.0), Encoding.MSGPACK)] * 2)[0])
    await wait_until(lambda: listener.received == [7.0, 7.0], what="the good batch")
    assert "not a msgpack batch" in caplog.text


async def test_a_latched_frame_sent_pretty_reaches_a_batching_json_reader_on_one_line(core) -> None:
    twist = {"linear": {"x": 1.5, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.5}}
    url = stream_url(core.url, "/pretty", type="geometry_msgs/msg/Twist")
    async with connect(url) as publisher:
        await publisher.send(json.dumps(twist, indent=2))  # every field named: forwarded as it came
        async with connect(stream_url(core.url, "/pretty")) as plain:
            assert "\n" in await asyncio.wait_for(plain.recv(), 5)  # the latched frame, as sent
        async with connect(stream_url(core.url, "/pretty", batch=1)) as batching:
            frame = await asyncio.wait_for(batching.recv(), 5)
    assert not batch.is_batch(frame) and json.loads(frame) == twist


class RawListener(Node):
    """Reads /burst raw (as the recorder does): a topic read only raw links in JSON."""

    def __init__(self, settings) -> None:
        super().__init__("batch_raw_listener", settings=settings)
        self.received: list[float] = []
        self.create_subscription(
            Twist, "/burst", lambda frame: self.received.append(json.loads(frame)["linear"]["x"]), 1000, raw=True
        )


@pytest.mark.parametrize("listener_type", [Listener, RawListener], ids=["msgpack link", "raw JSON link"])
async def test_a_subscriber_node_gets_a_burst_whole_and_in_order_through_its_link(start_node, listener_type) -> None:
    talker = await start_node(Talker)
    listener = await start_node(listener_type)
    await wait_until(lambda: talker.publisher.get_subscription_count() == 1, what="the link")
    talker.burst(500)
    await wait_until(lambda: len(listener.received) == 500, what="the whole burst")
    assert listener.received == [float(i) for i in range(500)]


async def test_the_core_splits_a_burst_for_its_own_readers_one_message_a_frame(core, start_node) -> None:
    talker = await start_node(Talker)
    count = 200
    async with (
        connect(stream_url(core.url, "/burst", queue=count, encoding="msgpack")) as packed,
        connect(stream_url(core.url, "/burst", queue=count)) as text,
    ):
        await wait_until(lambda: talker.publisher.get_subscription_count() == 1, what="the core's link")
        talker.burst(count)
        packed_frames = [await asyncio.wait_for(packed.recv(), 5) for _ in range(count)]
        text_frames = [await asyncio.wait_for(text.recv(), 5) for _ in range(count)]
    expected = [encode(_twist(float(i)), Encoding.MSGPACK) for i in range(count)]
    assert packed_frames == expected  # each message's bytes as its publisher made them
    assert [json.loads(frame)["linear"]["x"] for frame in text_frames] == [float(i) for i in range(count)]
