"""tf2's buffer without a network: lookups latest and at a time (interpolated: linear
translation, slerp rotation), chains up, down and across a tree of static and dynamic links,
tf2's exceptions with tf2's words, waits that end when data arrives or time is up, the cache's
reach, and messages moved between frames."""

from __future__ import annotations

import math
import threading
import time

import pytest

from services.ros.rclpy.duration import Duration
from services.ros.rclpy.task import Future
from services.ros.rclpy.time import Time
from services.ros.rospy.rostime import Duration as RospyDuration
from services.ros.rospy.rostime import Time as RospyTime
from services.ros.tf2_ros import (
    Buffer,
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
    TypeException,
)
from services.ros.tf2_ros.do_transform import (
    do_transform_point,
    do_transform_pose,
    do_transform_pose_with_covariance_stamped,
    do_transform_vector3,
)
from shared_models.builtin_interfaces import Time as TimeMsg
from shared_models.errors import SkydeckError
from shared_models.geometry_msgs import (
    Point,
    PointStamped,
    Pose,
    PoseStamped,
    PoseWithCovarianceStamped,
    Quaternion,
    Transform,
    TransformStamped,
    Vector3,
    Vector3Stamped,
)
from shared_models.std_msgs import Header

pytestmark = pytest.mark.timeout(30)


def _link(parent: str, child: str, seconds: float, x: float = 0.0, y: float = 0.0, z: float = 0.0, yaw: float = 0.0) -> TransformStamped:
    return TransformStamped(
        header=Header(stamp=TimeMsg.from_nsec(round(seconds * 1e9)), frame_id=parent),
        child_frame_id=child,
        transform=Transform(
            translation=Vector3(x=x, y=y, z=z), rotation=Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2))
        ),
    )


def _xy_yaw(t: TransformStamped) -> tuple[float, float, float]:
    q = t.transform.rotation
    return t.transform.translation.x, t.transform.translation.y, 2 * math.atan2(q.z, q.w)


def _close(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return all(math.isclose(p, q, abs_tol=1e-9) for p, q in zip(a, b, strict=True))


@pytest.fixture
def robot() -> Buffer:
    """map -> odom (static, the start pose), odom -> base_link (10 Hz for 1 s, driving +x and
    turning), base_link -> laser (static)."""
    buffer = Buffer()
    buffer.set_transform_static(_link("map", "odom", 0.0, x=1.0, y=2.0, yaw=math.pi / 2), "test")
    buffer.set_transform_static(_link("base_link", "laser", 0.0, x=0.1, z=0.2), "test")
    for i in range(11):
        buffer.set_transform(_link("odom", "base_link", 100 + i / 10, x=i / 10, yaw=i / 10), "test")
    return buffer


def test_latest_is_the_newest_common_time_and_says_so_in_its_stamp(robot: Buffer) -> None:
    t = robot.lookup_transform("odom", "base_link", Time())
    assert (t.header.frame_id, t.child_frame_id) == ("odom", "base_link")
    assert t.header.stamp == TimeMsg(sec=101, nanosec=0)
    assert _close(_xy_yaw(t), (1.0, 0.0, 1.0))
    static = robot.lookup_transform("base_link", "laser", Time())  # static links only: time 0
    assert static.header.stamp == TimeMsg(sec=0, nanosec=0) and static.transform.translation.z == 0.2


def test_at_a_time_between_samples_interpolates_linearly_and_by_slerp(robot: Buffer) -> None:
    t = robot.lookup_transform("odom", "base_link", Time(seconds=100, nanoseconds=250_000_000))
    assert t.header.stamp == TimeMsg(sec=100, nanosec=250_000_000)
    assert _close(_xy_yaw(t), (0.25, 0.0, 0.25))  # half-way between 0.2 and 0.3, in both
    exact = robot.lookup_transform("odom", "base_link", RospyTime(100, 300_000_000))  # rospy's Time too
    assert _close(_xy_yaw(exact), (0.3, 0.0, 0.3))


def test_slerp_keeps_constant_angular_speed_and_takes_the_short_way() -> None:
    buffer = Buffer()
    buffer.set_transform(_link("a", "b", 1.0, yaw=math.radians(170)), "test")
    buffer.set_transform(_link("a", "b", 2.0, yaw=math.radians(-170)), "test")  # 20 degrees on, across +-180
    for fraction in (0.25, 0.5, 0.75):
        yaw = _xy_yaw(buffer.lookup_transform("a", "b", Time(seconds=1 + fraction)))[2]
        assert math.isclose(math.remainder(yaw - math.radians(170 + 20 * fraction), math.tau), 0.0, abs_tol=1e-9)


def test_chains_up_down_and_across_static_and_dynamic_links(robot: Buffer) -> None:
    at = Time(seconds=100.5)
    # laser in map: map->odom (static) . odom->base_link (t) . base_link->laser (static)
    t = robot.lookup_transform("map", "laser", at)
    x_odom, yaw = 0.5 + 0.1 * math.cos(0.5), 0.5
    y_odom = 0.1 * math.sin(0.5)
    expected = (1.0 - y_odom, 2.0 + x_odom, math.pi / 2 + yaw)  # odom is turned 90 degrees in map
    assert _close(_xy_yaw(t), expected) and math.isclose(t.transform.translation.z, 0.2)
    back = robot.lookup_transform("laser", "map", at)  # the other way: the inverse
    p = do_transform_point(PointStamped(point=Point(x=t.transform.translation.x, y=t.transform.translation.y, z=0.2)), back)
    assert _close((p.point.x, p.point.y, p.point.z), (0.0, 0.0, 0.0))
    down = robot.lookup_transform("base_link", "odom", at)  # the source is the target's ancestor
    assert _close(_xy_yaw(down), (-0.5 * math.cos(0.5), 0.5 * math.sin(0.5), -0.5))


def test_a_frame_never_heard_of_is_a_lookup_exception_in_tf2s_words(robot: Buffer) -> None:
    with pytest.raises(LookupException) as raised:
        robot.lookup_transform("odom", "base_footprint", Time())
    assert str(raised.value) == '"base_footprint" passed to lookupTransform argument source_frame does not exist. '
    with pytest.raises(LookupException, match=r'^"world" passed to lookupTransform argument target_frame'):
        robot.lookup_transform("world", "odom", Time())
    assert isinstance(raised.value, TransformException) and isinstance(raised.value, SkydeckError)


def test_extrapolation_into_the_future_and_the_past_name_the_times_and_frames(robot: Buffer) -> None:
    with pytest.raises(ExtrapolationException) as future:
        robot.lookup_transform("map", "laser", Time(seconds=101.5))
    assert str(future.value) == (
        "Lookup would require extrapolation into the future.  Requested time 101.500000 but the latest data is "
        "at time 101.000000, when looking up transform from frame [laser] to frame [map]"
    )
    with pytest.raises(ExtrapolationException, match=r"into the past\.  Requested time 99\.000000 but the earliest data is at time 100\.000000"):
        robot.lookup_transform("odom", "base_link", Time(seconds=99))
    one = Buffer()
    one.set_transform(_link("a", "b", 5.0), "test")
    with pytest.raises(ExtrapolationException, match=r"^Lookup would require extrapolation at time 6\.000000, but only time 5\.000000 is in the buffer"):
        one.lookup_transform("a", "b", Time(seconds=6))


def test_two_trees_are_a_connectivity_exception(robot: Buffer) -> None:
    robot.set_transform(_link("world", "person", 100.5, x=3.0), "test")
    with pytest.raises(ConnectivityException) as raised:
        robot.lookup_transform("map", "person", Time())
    assert str(raised.value) == (
        "Could not find a connection between 'map' and 'person' because they are not part of the same tree."
        "Tf has two or more unconnected trees."
    )
    assert robot.can_transform("map", "person", Time(), return_debug_tuple=True) == (False, str(raised.value))


@pytest.mark.parametrize(
    ("frame", "reason"), [("", "in tf2 frame_ids cannot be empty"), ("/odom", "in tf2 frame_ids cannot start with a '/'")]
)
def test_invalid_frame_names_are_invalid_arguments(robot: Buffer, frame: str, reason: str) -> None:
    with pytest.raises(InvalidArgumentException, match=f'Invalid argument "{frame}" passed to lookupTransform argument target_frame - {reason}'):
        robot.lookup_transform(frame, "base_link", Time())
    assert robot.can_transform(frame, "base_link", Time(), return_debug_tuple=True) == (
        False, f'Invalid frame ID "{frame}" passed to canTransform argument target_frame - {reason}',
    )  # fmt: skip
    with pytest.raises(InvalidArgumentException, match="time must be an rclpy.time.Time, a rospy.Time"):
        robot.lookup_transform("odom", "base_link", 100.5)


def test_can_transform_and_identity(robot: Buffer) -> None:
    assert robot.can_transform("map", "laser", Time()) is True
    assert robot.can_transform("map", "laser", Time(seconds=200)) is False
    same = robot.lookup_transform("nowhere", "nowhere", Time(seconds=3))  # tf2: identity, even unknown
    assert _close(_xy_yaw(same), (0.0, 0.0, 0.0)) and same.header.stamp == TimeMsg(sec=3)


def test_a_timeout_waits_for_data_that_arrives_and_not_longer() -> None:
    buffer = Buffer()
    buffer.set_transform(_link("odom", "base_link", 1.0), "test")
    later = threading.Timer(0.2, lambda: buffer.set_transform(_link("odom", "base_link", 2.0, x=2.0), "test"))
    later.start()
    start = time.monotonic()
    t = buffer.lookup_transform("odom", "base_link", Time(seconds=1.5), timeout=Duration(seconds=5.0))
    waited = time.monotonic() - start
    assert _close(_xy_yaw(t), (1.0, 0.0, 0.0)) and waited < 4.0  # woken by the data, not the timeout
    start = time.monotonic()
    with pytest.raises(ExtrapolationException, match="into the future"):  # after the wait: what tf2 says
        buffer.lookup_transform("odom", "base_link", Time(seconds=9), timeout=RospyDuration(0.3))
    assert time.monotonic() - start >= 0.3
    assert buffer.can_transform("odom", "laser", Time(), timeout=0.1) is False  # seconds work too


def test_wait_for_transform_async_completes_when_the_frame_arrives() -> None:
    buffer = Buffer()
    future = buffer.wait_for_transform_async("map", "base_link", Time())
    assert isinstance(future, Future) and not future.done()
    buffer.set_transform_static(_link("map", "odom", 0.0, x=1.0), "test")
    assert not future.done()
    buffer.set_transform(_link("odom", "base_link", 3.0, x=2.0), "test")
    assert future.wait(5) and _close(_xy_yaw(future.result()), (3.0, 0.0, 0.0))
    assert buffer.wait_for_transform_async("map", "base_link", Time()).done()  # possible already


def test_old_data_beyond_the_cache_time_is_refused_and_pruned() -> None:
    buffer = Buffer(cache_time=Duration(seconds=2.0))
    for second in range(10):
        assert buffer.set_transform(_link("odom", "base_link", second, x=second), "test")
    assert buffer.set_transform(_link("odom", "base_link", 1.0), "test") is False  # TF_OLD_DATA
    with pytest.raises(ExtrapolationException, match="earliest data is at time 7.000000"):
        buffer.lookup_transform("odom", "base_link", Time(seconds=6))
    assert "buffer_length: 2.000" in buffer.all_frames_as_yaml()


def test_refused_transforms_leave_the_tree_untouched(caplog: pytest.LogCaptureFixture) -> None:
    buffer = Buffer()
    bad = _link("odom", "base_link", 1.0)
    bad.transform.rotation = Quaternion(x=0.0, y=0.0, z=0.0, w=2.0)
    assert buffer.set_transform(bad, "me") is False
    assert buffer.set_transform(_link("odom", "odom", 1.0), "me") is False
    assert "TF_DENORMALIZED_QUATERNION" in caplog.text and "TF_SELF_TRANSFORM" in caplog.text
    assert buffer.frame_names() == [] and buffer.all_frames_as_string() == ""
    with pytest.raises(TypeError, match="TransformStamped"):
        buffer.set_transform(Pose(), "me")  # type: ignore[arg-type]


def test_lookup_transform_full_holds_the_fixed_frame_still(robot: Buffer) -> None:
    # Where base_link was at 100.2 s, seen from base_link at 100.8 s, odom not moving between.
    t = robot.lookup_transform_full("base_link", Time(seconds=100.8), "base_link", Time(seconds=100.2), "odom")
    then_x, now_x, now_yaw = 0.2, 0.8, 0.8
    dx, dy = then_x - now_x, 0.0
    expected = (dx * math.cos(now_yaw) + dy * math.sin(now_yaw), -dx * math.sin(now_yaw), 0.2 - 0.8)
    assert _close(_xy_yaw(t), expected)


def test_transform_moves_stamped_messages_at_their_stamp(robot: Buffer) -> None:
    stamp = TimeMsg.from_nsec(100_500_000_000)
    point = PointStamped(header=Header(stamp=stamp, frame_id="laser"), point=Point(x=1.0))
    in_odom = robot.transform(point, "odom")
    assert in_odom.header.frame_id == "odom" and in_odom.header.stamp == stamp
    assert _close((in_odom.point.x, in_odom.point.y), (0.5 + 1.1 * math.cos(0.5), 1.1 * math.sin(0.5)))
    pose = PoseStamped(header=Header(stamp=stamp, frame_id="base_link"), pose=Pose(orientation=Quaternion(w=1.0)))
    moved = robot.transform(pose, "map", timeout=Duration(seconds=1))
    assert _close((moved.pose.position.x, moved.pose.position.y), (1.0, 2.5))
    with pytest.raises(TypeException, match="is not loaded or supported"):
        robot.transform(Header(stamp=stamp, frame_id="laser"), "odom")


def test_do_transform_functions_against_known_values() -> None:
    quarter = _link("odom", "base_link", 7.0, x=1.0, y=2.0, z=3.0, yaw=math.pi / 2)
    p = do_transform_point(PointStamped(point=Point(x=1.0, y=0.0, z=0.0)), quarter)
    assert _close((p.point.x, p.point.y, p.point.z), (1.0, 3.0, 3.0))
    assert p.header.frame_id == "odom" and p.header.stamp == TimeMsg(sec=7)  # the transform's header
    v = do_transform_vector3(Vector3Stamped(vector=Vector3(x=1.0)), quarter)  # a direction: not moved
    assert _close((v.vector.x, v.vector.y, v.vector.z), (0.0, 1.0, 0.0))
    assert quarter.transform.translation.x == 1.0  # and the transform is left as it was
    bare = do_transform_pose(Pose(position=Point(x=1.0), orientation=Quaternion(w=1.0)), quarter)  # ROS 2: a Pose
    assert isinstance(bare, Pose) and _close((bare.position.x, bare.position.y, bare.orientation.z), (1.0, 3.0, math.sin(math.pi / 4)))
    stamped = do_transform_pose(PoseStamped(pose=Pose(orientation=Quaternion(w=1.0))), quarter)  # ROS 1
    assert isinstance(stamped, PoseStamped) and stamped.header.frame_id == "odom"
    covariance = [0.0] * 36
    covariance[0], covariance[7], covariance[35] = 4.0, 1.0, 0.5  # var x, var y, var yaw
    moved = do_transform_pose_with_covariance_stamped(
        PoseWithCovarianceStamped.model_validate({"pose": {"pose": {"orientation": {"w": 1.0}}, "covariance": covariance}}),
        quarter,
    )
    c = moved.pose.covariance
    assert _close((c[0], c[7], c[35], c[1]), (1.0, 4.0, 0.5, 0.0))  # x and y swap under a quarter turn


def test_ros1_tf_transformer_answers_in_tuples_and_takes_leading_slashes() -> None:
    from services.ros.tf import Exception as TfException
    from services.ros.tf import TransformerROS

    tf_ = TransformerROS(True, RospyDuration(10.0))
    tf_.setTransformStatic(_link("map", "odom", 0.0, x=1.0))
    tf_.setTransform(_link("odom", "base_link", 5.0, x=2.0, yaw=math.pi / 2))
    trans, rot = tf_.lookupTransform("/map", "/base_link", RospyTime(0))
    assert trans == pytest.approx([3.0, 0.0, 0.0]) and rot == pytest.approx([0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])
    assert tf_.canTransform("/map", "base_link", RospyTime(0)) and tf_.frameExists("odom")
    assert tf_.getLatestCommonTime("/map", "/base_link") == RospyTime(5)
    ahead = PointStamped(header=Header(stamp=RospyTime(5), frame_id="/base_link"), point=Point(x=1.0))
    moved = tf_.transformPoint("/map", ahead)
    assert (moved.header.frame_id, moved.header.stamp) == ("/map", RospyTime(5))  # tf keeps the asked name and stamp
    assert (moved.point.x, moved.point.y) == pytest.approx((3.0, 1.0))
    assert tf_.asMatrix("map", ahead.header) @ [1.0, 0.0, 0.0, 1.0] == pytest.approx([3.0, 1.0, 0.0, 1.0])
    with pytest.raises(TfException, match="without a dedicated thread"):  # tf.Transformer has no listener
        tf_.waitForTransform("map", "base_link", RospyTime(0), RospyDuration(0.1))
    tf_.setUsingDedicatedThread(True)
    with pytest.raises(TfException, match='Invalid frame ID "nowhere" passed to canTransform argument source_frame'):
        tf_.waitForTransform("map", "nowhere", RospyTime(0), RospyDuration(0.1))
