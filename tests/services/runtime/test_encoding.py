"""Binary frames (msgpack), negotiated per connection: same messages as JSON readers, byte arrays
as bytes, bad binary frames refused like bad JSON, CBOR refused with a reason."""

from __future__ import annotations

import asyncio
import base64
import json

import ormsgpack
import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed

from services.runtime import Node
from services.runtime.edge.encoding import Encoding, Frames, negotiate
from services.runtime.edge.frames import FrameRejected
from services.runtime.edge.links import stream_url
from shared_models.geometry_msgs import PoseStamped
from shared_models.sensor_msgs import Image
from tests.bad_frames import oversized_header
from tests.conftest import wait_until

pytestmark = pytest.mark.timeout(60)


class Camera(Node):
    def __init__(self, settings) -> None:
        super().__init__("camera_probe", settings=settings)
        self.images: list[Image] = []
        self.image = self.create_publisher(Image, "/camera/image_raw", 10)
        self.pose = self.create_publisher(PoseStamped, "/pose", 10)
        self.create_subscription(Image, "/camera/upload", self.images.append, 10)


def _image(width: int = 64, height: int = 48) -> Image:
    data = bytes((x * 7 + y * 13) % 256 for y in range(height) for x in range(width * 3))
    return Image(height=height, width=width, encoding="rgb8", step=width * 3, data=data)


async def _closed(websocket) -> tuple[int | None, str]:
    with pytest.raises(ConnectionClosed):
        await asyncio.wait_for(websocket.recv(), 5)
    return websocket.close_code, websocket.close_reason


def test_negotiation_reads_the_query_then_the_subprotocol() -> None:
    assert negotiate({}, []) == (Encoding.JSON, None)
    assert negotiate({"encoding": "msgpack"}, []) == (Encoding.MSGPACK, None)
    assert negotiate({}, ["skydeck.msgpack"]) == (Encoding.MSGPACK, "skydeck.msgpack")
    assert negotiate({}, ["chat", "skydeck.json"]) == (Encoding.JSON, "skydeck.json")
    for query, subprotocols in (({"encoding": "cbor"}, []), ({}, ["skydeck.cbor"]), ({"encoding": "bson"}, [])):
        with pytest.raises(FrameRejected) as refused:
            negotiate(query, subprotocols)
        assert refused.value.code == 1008 and "msgpack" in refused.value.reason


def test_frames_make_each_encoding_once_from_whatever_they_have() -> None:
    image = _image()
    made = Frames(image)
    assert made.packed is made.packed and made.json is made.json
    from_binary = Frames.received(made.packed, Image)
    assert from_binary.json == image.model_dump_json()  # standard base64, as the model writes it
    untyped = Frames.received(made.packed, None)  # a type this process does not know
    assert json.loads(untyped.json) == json.loads(image.model_dump_json())
    nested = Frames.received(ormsgpack.packb({"images": [{"data": b"\x00\xff"}], "n": 1}), None)
    assert json.loads(nested.json) == {"images": [{"data": "AP8="}], "n": 1}  # byte arrays at any depth


@pytest.mark.parametrize("via_core", [False, True])
async def test_a_binary_reader_and_a_json_reader_get_the_same_messages(core, start_node, via_core) -> None:
    camera = await start_node(Camera)
    base = core.url if via_core else camera.url
    readers = camera._participant.endpoints["/camera/image_raw"].outboxes
    async with (
        connect(stream_url(base, "/camera/image_raw"), max_size=None) as text_reader,
        connect(stream_url(base, "/camera/image_raw"), subprotocols=["skydeck.msgpack"], max_size=None) as binary_reader,
    ):
        assert binary_reader.subprotocol == "skydeck.msgpack"
        if not via_core:
            await wait_until(lambda: len(readers) == 2, what="both readers")
        else:
            await wait_until(lambda: len(readers) >= 1, what="the core to link")
        sent = [_image(), _image(32, 16)]
        for image in sent:
            camera.image.publish(image)
        for image in sent:
            as_text = await asyncio.wait_for(text_reader.recv(), 5)
            as_binary = await asyncio.wait_for(binary_reader.recv(), 5)
            assert isinstance(as_text, str) and isinstance(as_binary, bytes)
            unpacked = ormsgpack.unpackb(as_binary)
            assert unpacked["data"] == image.data  # bytes, not base64 or a list of numbers
            assert base64.b64decode(json.loads(as_text)["data"]) == image.data
            assert Image.model_validate(unpacked) == Image.model_validate_json(as_text)


async def test_an_image_round_trips_bit_exact_in_binary(core, start_node) -> None:
    camera = await start_node(Camera)
    image = _image(160, 120)
    async with connect(stream_url(core.url, "/camera/upload", encoding="msgpack", mode="publish")) as uploader:
        await uploader.send(ormsgpack.packb(image.model_dump()))
        await wait_until(lambda: camera.images, what="the image to arrive")
    assert camera.images[0].data == image.data and camera.images[0] == image


@pytest.mark.parametrize(
    ("frame", "expected"),
    [
        (b"\x92\x01", "msgpack"),  # truncated: an array of two, one element
        (ormsgpack.packb({"height": "tall"}), "height"),  # the wrong type for a field
        (ormsgpack.packb([1, 2, 3]), "Image"),  # not a map at all
        (b"\xdd\xff\xff\xff\xff", "msgpack"),  # a 4-billion-element array in five bytes
        (b"\xc6\x7f\xff\xff\xff", "msgpack"),  # a 2 GiB byte string in five bytes
    ],
)
@pytest.mark.parametrize("via_core", [False, True])
async def test_bad_binary_frames_close_with_1007_and_nothing_else_is_disturbed(
    core, start_node, frame, expected, via_core
) -> None:
    camera = await start_node(Camera)
    base = core.url if via_core else camera.url  # the gateway refuses them as the node does
    async with connect(stream_url(base, "/camera/upload", encoding="msgpack")) as websocket:
        await websocket.send(frame)
        code, reason = await _closed(websocket)
    assert code == 1007 and expected in reason
    async with connect(stream_url(base, "/camera/upload", encoding="msgpack")) as websocket:
        await websocket.send(ormsgpack.packb(_image().model_dump()))
        await wait_until(lambda: camera.images, what="the node to keep serving")


async def test_frames_of_the_other_kind_and_oversized_ones_are_refused(start_node) -> None:
    camera = await start_node(Camera)
    async with connect(stream_url(camera.url, "/camera/upload", encoding="msgpack")) as websocket:
        await websocket.send(_image().model_dump_json())  # text on a msgpack socket
        assert (await _closed(websocket))[0] == 1003
    async with connect(stream_url(camera.url, "/camera/upload"), max_size=None) as websocket:
        await websocket.send(ormsgpack.packb(_image().model_dump()))  # binary on a JSON socket
        assert (await _closed(websocket))[0] == 1003
    async with connect(stream_url(camera.url, "/camera/upload", encoding="msgpack"), max_size=None) as websocket:
        websocket.transport.write(oversized_header(camera.settings.max_message_bytes + 1, binary=True))
        assert (await _closed(websocket))[0] == 1009


async def test_cbor_is_refused_with_a_reason_that_says_what_to_ask_for(start_node) -> None:
    camera = await start_node(Camera)
    async with connect(stream_url(camera.url, "/pose", encoding="cbor")) as websocket:
        code, reason = await _closed(websocket)
    assert code == 1008 and "cbor" in reason and "msgpack" in reason


async def test_nodes_link_to_each_other_in_msgpack(core, start_node) -> None:
    camera = await start_node(Camera)
    received: list[PoseStamped] = []

    class Listener(Node):
        def __init__(self, settings) -> None:
            super().__init__("pose_listener", settings=settings)
            self.create_subscription(PoseStamped, "/pose", received.append, 10)

    await start_node(Listener)
    readers = camera._participant.endpoints["/pose"].outboxes
    await wait_until(lambda: len(readers) == 1, what="the listener to link")
    (link,) = readers
    assert link.encoding is Encoding.MSGPACK
    camera.pose.publish(PoseStamped(pose={"position": {"x": 2.5}}))
    await wait_until(lambda: received, what="the pose to arrive")
    assert received[0].pose.position.x == 2.5 and received[0].header.seq == 1
