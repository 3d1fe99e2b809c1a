"""rclpy.time, rclpy.duration, rclpy.qos and rclpy.logging against rclpy's documented behaviour."""

from __future__ import annotations

import pytest

from services.ros.rclpy.clock import Clock, ClockType
from services.ros.rclpy.duration import Duration
from services.ros.rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    InvalidQoSProfileException,
    QoSPresetProfiles,
    QoSProfile,
    ReliabilityPolicy,
    qos_profile,
    qos_profile_sensor_data,
)
from services.ros.rclpy.time import Time
from shared_models.builtin_interfaces import Duration as DurationMsg
from shared_models.builtin_interfaces import Time as TimeMsg


def test_time_minus_time_is_a_duration_that_compares() -> None:
    start = Time(seconds=10, clock_type=ClockType.ROS_TIME)
    now = Time(seconds=12, nanoseconds=5, clock_type=ClockType.ROS_TIME)
    assert now - start > Duration(seconds=2)
    assert now - start == Duration(nanoseconds=2_000_000_005)
    assert (now - Duration(seconds=2)).nanoseconds == 10_000_000_005
    assert (start + Duration(seconds=0.5)).nanoseconds == 10_500_000_000
    assert (Duration(seconds=1) + start).clock_type == ClockType.ROS_TIME
    assert start < now and now >= start and start != now


def test_times_of_different_clocks_and_other_types_do_not_compare() -> None:
    with pytest.raises(TypeError, match="different clock types"):
        _ = Time(seconds=1, clock_type=ClockType.ROS_TIME) < Time(seconds=2)
    with pytest.raises(TypeError, match="different clock types"):
        _ = Time(seconds=1, clock_type=ClockType.ROS_TIME) - Time(seconds=2)
    with pytest.raises(TypeError, match="Can't compare time with object of type"):
        _ = Time(seconds=1) < 2
    with pytest.raises(TypeError, match="Can't compare duration"):
        _ = Duration(seconds=1) < 1.0


def test_time_and_duration_messages_round_trip() -> None:
    t = Time(seconds=3, nanoseconds=7)
    assert t.to_msg() == TimeMsg(sec=3, nanosec=7)
    assert Time.from_msg(TimeMsg(sec=3, nanosec=7)).nanoseconds == 3_000_000_007
    assert Time.from_msg(TimeMsg(sec=3)).clock_type == ClockType.ROS_TIME
    assert t.seconds_nanoseconds() == (3, 7)
    assert Duration(seconds=-1.5).to_msg() == DurationMsg(sec=-2, nanosec=500_000_000)
    assert Duration.from_msg(DurationMsg(sec=2, nanosec=1)).nanoseconds == 2_000_000_001
    with pytest.raises(ValueError, match="must not be negative"):
        Time(seconds=-1)


def test_duration_arithmetic() -> None:
    assert Duration(seconds=1) - Duration(seconds=3) == Duration(seconds=-2)
    assert Duration(seconds=2) * 1.5 == Duration(seconds=3)
    assert -Duration(seconds=1) < Duration()


def test_clocks_read_their_time() -> None:
    system, steady = Clock().now(), Clock(clock_type=ClockType.STEADY_TIME).now()
    assert system.clock_type == ClockType.SYSTEM_TIME and system.nanoseconds > 1_600_000_000 * 10**9
    assert steady.clock_type == ClockType.STEADY_TIME


def test_qos_profiles_as_rclpy() -> None:
    assert qos_profile(10).depth == 10 and qos_profile(10).history == HistoryPolicy.KEEP_LAST
    assert qos_profile_sensor_data.depth == 5 and qos_profile_sensor_data.reliability == ReliabilityPolicy.BEST_EFFORT
    assert QoSPresetProfiles.SENSOR_DATA.value is qos_profile_sensor_data
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    assert latched.latched and latched.queue_depth == 1
    assert QoSProfile(history=HistoryPolicy.KEEP_ALL).queue_depth > 1000
    assert QoSProfile(history=HistoryPolicy.KEEP_LAST).queue_depth == 10  # depth 0: the default
    with pytest.raises(InvalidQoSProfileException, match="History and/or depth"):
        QoSProfile()
    with pytest.raises(TypeError, match="QoSProfile or an int"):
        qos_profile("10")
