"""The one JSON-schema writer (recordings and Foxglove's channels): schemas Lichtblick's and
Foxglove's readers take, that every message's own JSON fits, with times as both read them."""

from __future__ import annotations

import json
from typing import Any

import pytest

from shared_models import Message, all_interfaces
from shared_models.builtin_interfaces import Duration, Time
from shared_models.catalogue import load_catalogue
from shared_models.geometry_msgs import Point, PoseStamped
from shared_models.json_schema import (
    has_time,
    json_schema,
    json_schema_text,
    with_nsec,
    without_nsec,
)
from shared_models.std_msgs import Header

load_catalogue()
MESSAGES = {name: cls for name, cls in all_interfaces().items() if isinstance(cls, type) and issubclass(cls, Message)}
PLAIN = {"boolean", "string", "number", "integer", "object", "array"}


def _readable(schema: dict[str, Any], where: str) -> None:
    """What Lichtblick's parseJsonSchema takes: an object with properties, each of a plain type;
    base64 the only content encoding, and not inside arrays; array items of a plain type."""
    assert schema.get("type") == "object" and isinstance(schema.get("properties"), dict), where
    for name, field in schema["properties"].items():
        here = f"{where}.{name}"
        assert field.get("type") in PLAIN and "anyOf" not in field and "$ref" not in field, here
        if field["type"] == "string":
            assert field.get("contentEncoding") in (None, "base64"), here
        if field["type"] == "object":
            _readable(field, here)
        if field["type"] == "array":
            items = field["items"]
            assert items.get("type") in PLAIN - {"array"} and "contentEncoding" not in items, here
            if items["type"] == "object":
                _readable(items, here + "[]")


@pytest.mark.parametrize("name", sorted(MESSAGES))
def test_every_message_types_schema_is_one_foxglove_and_lichtblick_read(name: str) -> None:
    schema = json.loads(json_schema_text(MESSAGES[name]))
    assert schema["title"] == name and "$defs" not in schema
    _readable(schema, name)


@pytest.mark.parametrize("name", sorted(MESSAGES))
def test_a_message_as_published_fits_its_schema(name: str) -> None:
    jsonschema_rs = pytest.importorskip("jsonschema_rs")
    try:
        message = MESSAGES[name]()
    except Exception:  # a type with a required field has no message by default
        pytest.skip(f"{name} has no default message")
    validator = jsonschema_rs.Draft202012Validator(json_schema(MESSAGES[name]))
    frame = message.model_dump_json()
    assert validator.is_valid(json.loads(frame)), list(validator.iter_errors(json.loads(frame)))[:1]
    assert validator.is_valid(json.loads(with_nsec(frame)))  # as the Foxglove endpoint sends it


def test_times_declare_ros_2s_nanosec_and_foxgloves_nsec() -> None:
    stamp = json_schema(PoseStamped)["properties"]["header"]["properties"]["stamp"]["properties"]
    assert set(stamp) == {"sec", "nanosec", "nsec"} and stamp["nsec"]["type"] == "integer"
    assert set(json_schema(Duration)["properties"]) == {"sec", "nanosec", "nsec"}
    assert has_time(PoseStamped) and has_time(Time) and not has_time(Point)


def test_nsec_goes_beside_each_nanosec_and_back() -> None:
    frame = PoseStamped(header=Header(stamp=Time(sec=3, nanosec=250))).model_dump_json()
    foxglove = with_nsec(frame)
    assert json.loads(foxglove)["header"]["stamp"] == {"sec": 3, "nanosec": 250, "nsec": 250}
    assert json.loads(without_nsec(foxglove)) == json.loads(frame)
    # A time written Foxglove's way only gets ROS 2's name; text with no nsec is left as it is.
    assert json.loads(without_nsec('{"sec": 1, "nsec": 7}')) == {"sec": 1, "nanosec": 7}
    assert without_nsec(frame) is frame
    # Never inside a string, where the quotes are escaped.
    text = json.dumps({"data": '{"nanosec":5}'})
    assert with_nsec(text) == text
