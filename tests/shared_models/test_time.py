"""builtin_interfaces Time and Duration: ROS 1 and ROS 2 spellings, comparison, arithmetic, and
the JSON that stays {"sec", "nanosec"}."""

from __future__ import annotations

import json
import math

import pytest
from pydantic import ValidationError

from shared_models.builtin_interfaces import Duration, Time
from shared_models.std_msgs import Header


class TestConstruction:
    def test_ros2_keywords(self) -> None:
        stamp = Time(sec=12, nanosec=500)
        assert (stamp.sec, stamp.nanosec) == (12, 500)
        assert json.loads(stamp.model_dump_json()) == {"sec": 12, "nanosec": 500}

    def test_ros1_positional_and_keywords(self) -> None:
        assert Time(5, 500) == Time(sec=5, nanosec=500)
        assert Time(5) == Time(sec=5)
        assert Time(secs=5, nsecs=500) == Time(sec=5, nanosec=500)
        assert Duration(nsecs=7) == Duration(sec=0, nanosec=7)

    def test_float_seconds_are_split_as_genpy_does(self) -> None:
        assert Duration(0.5) == Duration(sec=0, nanosec=500_000_000)
        assert Time(1.25) == Time(sec=1, nanosec=250_000_000)
        assert Duration(secs=2.5) == Duration(sec=2, nanosec=500_000_000)

    def test_ros1_forms_carry_nanoseconds_and_normalise_negative_spans(self) -> None:
        assert Time(1, 2_000_000_001) == Time(sec=3, nanosec=1)
        assert Duration(-1.5) == Duration(sec=-2, nanosec=500_000_000)
        assert Duration(0, -1) == Duration(sec=-1, nanosec=999_999_999)

    def test_bad_forms(self) -> None:
        with pytest.raises(TypeError, match="not both"):
            Time(1, nsecs=2)
        with pytest.raises(TypeError, match="got both secs and sec"):
            Time(sec=1, secs=2)
        with pytest.raises(TypeError, match="at most 2 positional"):
            Duration(1, 2, 3)
        with pytest.raises(ValidationError):
            Time("1")
        with pytest.raises(ValidationError):
            Duration(math.nan)
        with pytest.raises(ValidationError):
            Time(sec=1.5)  # the ROS 2 keyword is the int32 field itself
        with pytest.raises(ValidationError):
            Time(2.0**31)  # past int32 seconds

    def test_the_json_does_not_take_ros1_names(self) -> None:
        # The wire keeps ROS 2's names; the ROS 1 spellings are a Python convenience.
        with pytest.raises(ValidationError, match="extra"):
            Time.model_validate_json('{"secs": 1, "nsecs": 2}')
        header = Header.model_validate_json('{"stamp": {"sec": 1, "nanosec": 2}}')
        assert header.stamp == Time(1, 2)


class TestConversions:
    def test_to_and_from(self) -> None:
        stamp = Time(sec=3, nanosec=250_000_000)
        assert stamp.to_sec() == 3.25
        assert stamp.to_seconds() == 3.25
        assert stamp.to_nsec() == 3_250_000_000
        assert Time.from_sec(3.25) == stamp
        assert Time.from_seconds(3.25) == stamp
        assert Time.from_nsec(3_250_000_000) == stamp
        assert Duration.from_sec(-0.25) == Duration(sec=-1, nanosec=750_000_000)
        assert Duration.from_sec(-0.25).to_sec() == -0.25
        assert isinstance(Duration.from_nsec(1), Duration)
        assert Time().is_zero() and not Time(0, 1).is_zero()

    def test_secs_and_nsecs_read_and_write_the_ros2_fields(self) -> None:
        stamp = Time(sec=1, nanosec=2)
        assert (stamp.secs, stamp.nsecs) == (1, 2)
        stamp.secs = 10
        stamp.nsecs = 20
        assert (stamp.sec, stamp.nanosec) == (10, 20)
        assert json.loads(stamp.model_dump_json()) == {"sec": 10, "nanosec": 20}
        header = Header()
        header.stamp.secs = 4
        assert header.stamp.sec == 4


class TestComparison:
    def test_order_within_a_type(self) -> None:
        assert Time(1, 5) < Time(1, 6) < Time(2, 0)
        assert Time(2) <= Time(2) and Time(2) >= Time(2)
        assert Time(3) > Time(2, 999_999_999)
        assert not Time(2) < Time(2)
        assert Duration(-1) < Duration(0) < Duration(0.5)
        assert max(Time(1), Time(3), Time(2)) == Time(3)
        assert sorted([Duration(2), Duration(-1), Duration(0.5)]) == [
            Duration(-1),
            Duration(0.5),
            Duration(2),
        ]

    def test_equality_and_hash(self) -> None:
        assert Time(1, 0) == Time(sec=1)
        assert Time(1) != Time(1, 1)
        assert Time(1) != Duration(1)  # a point is not a span, as in ROS
        assert {Time(1): "a"}[Time(1)] == "a"
        assert hash(Time(1)) != hash(Duration(1))

    def test_time_and_duration_do_not_order(self) -> None:
        with pytest.raises(TypeError):
            _ = Time(1) < Duration(2)
        with pytest.raises(TypeError):
            _ = Duration(1) >= Time(2)


class TestArithmetic:
    def test_time_minus_time_is_a_duration(self) -> None:
        elapsed = Time(10, 100) - Time(7, 200)
        assert isinstance(elapsed, Duration)
        assert elapsed == Duration(sec=2, nanosec=999_999_900)
        assert Time(1) - Time(2) == Duration(-1)

    def test_time_and_duration(self) -> None:
        assert Time(1) + Duration(2.5) == Time(3, 500_000_000)
        assert Duration(2.5) + Time(1) == Time(3, 500_000_000)
        assert isinstance(Duration(1) + Time(1), Time)
        assert Time(3) - Duration(0.5) == Time(2.5)
        start = Time(100)
        assert Time(103) - start > Duration(2)  # the course's "timed square" check

    def test_duration_algebra(self) -> None:
        assert Duration(1) + Duration(0.5) == Duration(1.5)
        assert Duration(1) - Duration(1.5) == Duration(-0.5)
        assert -Duration(1.5) == Duration(-1.5)
        assert abs(Duration(-2)) == Duration(2)
        assert Duration(1) * 2.5 == Duration(2.5)
        assert 3 * Duration(0.5) == Duration(1.5)
        assert Duration(3) / 2 == Duration(1.5)
        assert Duration(3) / Duration(1.5) == 2.0

    @pytest.mark.parametrize(
        "operation",
        [
            lambda: Time(1) + Time(1),
            lambda: Duration(1) - Time(1),
            lambda: Time(1) + 1.0,
            lambda: Duration(1) * Duration(1),
            lambda: Duration(1) * math.inf,
            lambda: Duration(1) / "2",
        ],
    )
    def test_meaningless_operations_are_refused(self, operation) -> None:
        with pytest.raises(TypeError):
            operation()

    def test_results_past_int32_seconds_are_refused(self) -> None:
        with pytest.raises(ValidationError):
            Time(2**31 - 1) + Duration(1)
