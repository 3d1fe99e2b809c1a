"""The dashboard's msgpack decoder (web_ui/static/js/msgpack.js), run in Chromium on frames
made by the core's own encoder (ormsgpack): every kind of value decodes to what JSON gives,
bytes come as a Uint8Array, and truncated, unknown or bomb-sized frames throw, never allocate."""

from __future__ import annotations

import json
from collections.abc import Iterator

import ormsgpack
import pytest

from shared_models.geometry_msgs import PoseStamped
from shared_models.sensor_msgs import Image
from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import System, started

pytestmark = [pytest.mark.browser, pytest.mark.timeout(60)]


@pytest.fixture(scope="module")
def system() -> Iterator[System]:
    with started() as running:
        yield running


@pytest.fixture(scope="module")
def page(system: System, browser: object) -> Iterator[object]:
    with open_dashboard(browser, system.url, "window.skydeck !== undefined") as (page, recorder):
        yield page
        assert recorder.errors == []


def _decode(page, frame: bytes) -> dict:  # type: ignore[no-untyped-def]
    """What decode() makes of ``frame``: the value (bytes as a list of numbers) or its error."""
    return page.evaluate(  # type: ignore[no-any-return]
        """async (frame) => {
          const { decode } = await import('/static/js/msgpack.js');
          try {
            const value = decode(new Uint8Array(frame));
            return { value: JSON.parse(JSON.stringify(value, (k, v) => v instanceof Uint8Array ? { bytes: [...v] } : v)) };
          } catch (error) {
            return { error: `${error.constructor.name}: ${error.message}` };
          }
        }""",
        list(frame),
    )


VALUES = [
    0, 127, 128, 255, 65535, 65536, 2**32 - 1, 2**32, 2**53 - 1, -1, -32, -33, -128, -129, -32768, -(2**31), -(2**53 - 1),
    0.5, -1.25e300, True, False, None, "", "é✓", "x" * 40, "y" * 300, "z" * 70000,
    [], list(range(20)), {"a": {"b": [1, {"c": None}]}}, {f"k{i}": i for i in range(20)},
]


def test_every_kind_of_value_decodes_as_json_gives_it(page) -> None:  # type: ignore[no-untyped-def]
    for value in VALUES:
        assert _decode(page, ormsgpack.packb(value)) == {"value": json.loads(json.dumps(value))}, value


def test_messages_decode_with_their_bytes_as_bytes(page) -> None:  # type: ignore[no-untyped-def]
    image = Image(width=4, height=2, encoding="rgb8", step=12, data=bytes(range(24)))
    packed = ormsgpack.packb(image, option=ormsgpack.OPT_SERIALIZE_PYDANTIC)
    decoded = _decode(page, packed)["value"]
    assert decoded["data"] == {"bytes": list(range(24))} and decoded["step"] == 12 and decoded["encoding"] == "rgb8"
    pose = PoseStamped()
    pose.pose.position.x = 1.5
    expected = json.loads(pose.model_dump_json())
    assert _decode(page, ormsgpack.packb(pose, option=ormsgpack.OPT_SERIALIZE_PYDANTIC))["value"] == expected


@pytest.mark.parametrize(
    ("frame", "expected"),
    [
        (b"", "truncated"),
        (b"\x92\x01", "2 elements in 1 bytes"),  # an array of two, one element
        (b"\xc4\x05ab", "truncated"),  # 5 bytes of binary promised, 2 given
        (b"\xdd\xff\xff\xff\xff", "4294967295 elements"),  # a 4-billion-element array in five bytes
        (b"\xdf\x7f\xff\xff\xff", "elements"),  # a map of 2^31 pairs
        (b"\xc6\x7f\xff\xff\xff", "truncated"),  # a 2 GiB byte string in five bytes
        (b"\xc1", "not supported"),  # never used
        (b"\xd4\x01\x00", "not supported"),  # an extension type
        (b"\xa2\xff\xfe", "not UTF-8"),
        (b"\x01\x02", "after the value"),
        (b"\x91" * 100 + b"\x00", "nested deeper"),
        (b"\x81\x90\x00", "map key"),
    ],
)
def test_malformed_frames_throw_a_msgpack_error(page, frame: bytes, expected: str) -> None:  # type: ignore[no-untyped-def]
    error = _decode(page, frame).get("error", "")
    assert error.startswith("MsgpackError") and expected in error, error


def test_a_proto_key_is_data_not_a_prototype(page) -> None:  # type: ignore[no-untyped-def]
    frame = ormsgpack.packb({"__proto__": {"polluted": 1}})
    result = page.evaluate(
        """async (frame) => {
          const { decode } = await import('/static/js/msgpack.js');
          const value = decode(new Uint8Array(frame));
          return { own: Object.keys(value), polluted: value.polluted === 1 || {}.polluted === 1 };
        }""",
        list(frame),
    )
    assert result == {"own": ["__proto__"], "polluted": False}
