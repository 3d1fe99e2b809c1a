"""JSON is taken as typed: no lax coercion of booleans into numbers or strings into numbers."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from shared_models.geometry_msgs import Point, Twist
from shared_models.ros_workshop import FlyCommandRequest
from shared_models.std_msgs import Int32, String


@pytest.mark.parametrize(
    ("model", "frame"),
    [
        (FlyCommandRequest, '{"x": true, "y": false}'),  # found by schemathesis: flew to (1, 0)
        (Point, '{"x": "1.5"}'),
        (Int32, '{"data": 2.0}'),
        (Int32, '{"data": "3"}'),
        (String, '{"data": 5}'),
    ],
)
def test_mistyped_json_is_refused(model, frame) -> None:
    with pytest.raises(ValidationError):
        model.model_validate_json(frame)


def test_integers_are_floats_and_nested_dicts_still_work() -> None:
    assert FlyCommandRequest.model_validate_json('{"x": 5, "y": -3}').x == 5.0
    assert Twist(linear={"x": 1}).linear.x == 1.0
