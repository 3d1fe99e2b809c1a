"""ROS 1's ``tf.Transformer``, ``tf.TransformerROS`` and ``tf.TransformListener``, on a tf2 Buffer.

As Noetic's tf: ``lookupTransform`` answers ``([x, y, z], [x, y, z, w])``, frame names may
start with '/', ``waitForTransform`` raises ``tf.Exception`` with tf2's reason when the time is up,
and ``transformPoint``/``transformPose``/... move stamped messages into a frame at their stamp.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from services.ros.errors import NotProvidedError, not_provided
from services.ros.rospy.rostime import Time as RospyTime
from services.ros.tf2_ros.buffer import Buffer
from services.ros.tf2_ros.do_transform import (
    do_transform_point,
    do_transform_pose_stamped,
    do_transform_quaternion,
    do_transform_vector3,
)
from services.ros.tf2_ros.exceptions import TransformException
from services.ros.tf2_ros.transform_listener import TransformListener as Tf2Listener
from services.ros.tf_transformations import quaternion_matrix, translation_matrix
from shared_models.geometry_msgs import (
    PointStamped,
    PoseStamped,
    QuaternionStamped,
    TransformStamped,
    Vector3Stamped,
)
from shared_models.std_msgs import Header

__all__ = ["TransformListener", "Transformer", "TransformerROS"]

Pair = tuple[list[float], list[float]]


def _strip(frame: str) -> str:
    return frame[1:] if isinstance(frame, str) and frame.startswith("/") else frame


def _raise_unless(result: tuple[bool, str], source_frame: str, target_frame: str) -> None:
    """``waitForTransform``'s end: tf.Exception with tf2's reason if the wait ran out."""
    ok, error = result
    if not ok:
        raise TransformException(error or f'no such transformation: "{source_frame}" -> "{target_frame}"')


def _pair(transform: TransformStamped) -> Pair:
    t, r = transform.transform.translation, transform.transform.rotation
    return [t.x, t.y, t.z], [r.x, r.y, r.z, r.w]


class Transformer:
    """tf's transform store: ``setTransform``, ``lookupTransform``, ``canTransform``, ..."""

    def __init__(self, interpolate: bool = True, cache_time: Any = None) -> None:
        self._buffer = Buffer(cache_time, debug=False)
        self._using_dedicated_thread = False

    def setTransform(self, transform: TransformStamped, authority: str = "default_authority") -> None:
        self._buffer.set_transform(transform, authority)

    def setTransformStatic(self, transform: TransformStamped, authority: str = "default_authority") -> None:
        self._buffer.set_transform_static(transform, authority)

    def lookupTransform(self, target_frame: str, source_frame: str, time: Any) -> Pair:
        """``(translation, rotation)`` of ``source_frame`` in ``target_frame`` at ``time``
        (``rospy.Time(0)``: the latest)."""
        return _pair(self._buffer.lookup_transform(_strip(target_frame), _strip(source_frame), time))

    def lookupTransformFull(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Pair:
        return _pair(
            self._buffer.lookup_transform_full(
                _strip(target_frame), target_time, _strip(source_frame), source_time, _strip(fixed_frame)
            )
        )

    def canTransform(self, target_frame: str, source_frame: str, time: Any) -> bool:
        return bool(self._buffer.can_transform(_strip(target_frame), _strip(source_frame), time))

    def canTransformFull(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> bool:
        return bool(
            self._buffer.can_transform_full(
                _strip(target_frame), target_time, _strip(source_frame), source_time, _strip(fixed_frame)
            )
        )

    def waitForTransform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Any, polling_sleep_duration: Any = None
    ) -> None:
        """Block until the transform can be had, or raise ``tf.Exception`` after ``timeout``."""
        self._check_listening()
        _raise_unless(
            self._buffer.can_transform(_strip(target_frame), _strip(source_frame), time, timeout, return_debug_tuple=True),
            source_frame, target_frame,
        )  # fmt: skip

    def waitForTransformFull(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str,
        timeout: Any, polling_sleep_duration: Any = None,
    ) -> None:  # fmt: skip
        self._check_listening()
        _raise_unless(
            self._buffer.can_transform_full(
                _strip(target_frame), target_time, _strip(source_frame), source_time, _strip(fixed_frame), timeout,
                return_debug_tuple=True,
            ),
            source_frame, target_frame,
        )  # fmt: skip

    def _check_listening(self) -> None:
        if not self._using_dedicated_thread:
            raise TransformException(
                "cannot wait for transform without a dedicated thread that listens to incoming TF messages "
                "(use tf.TransformListener, not tf.Transformer)"
            )

    def getLatestCommonTime(self, source_frame: str, dest_frame: str) -> RospyTime:
        """The newest time both frames have data for, as a ``rospy.Time``."""
        common = self._buffer.get_latest_common_time(_strip(source_frame), _strip(dest_frame))
        return RospyTime.from_nsec(common.to_nsec())  # type: ignore[no-any-return]

    def frameExists(self, frame_id: str) -> bool:
        return self._buffer.frame_exists(frame_id)

    def getFrameStrings(self) -> list[str]:
        return self._buffer.frame_names()

    def allFramesAsString(self) -> str:
        return self._buffer.all_frames_as_string()

    def allFramesAsYAML(self) -> str:
        return self._buffer.all_frames_as_yaml()

    def clear(self) -> None:
        self._buffer.clear()

    def setUsingDedicatedThread(self, value: bool) -> None:
        self._using_dedicated_thread = value

    def getTFPrefix(self) -> str:
        return ""  # tf2 has no tf_prefix

    def lookupTwist(self, *args: Any, **kwargs: Any) -> Any:
        raise NotProvidedError(not_provided("tf.TransformListener.lookupTwist"))

    lookupTwistFull = lookupTwist

    def allFramesAsDot(self, *args: Any) -> Any:
        raise NotProvidedError(not_provided("tf.TransformListener.allFramesAsDot"))


class TransformerROS(Transformer):
    """A Transformer that also moves ROS messages between frames."""

    def asMatrix(self, target_frame: str, hdr: Header) -> np.ndarray:
        """The 4x4 matrix taking points of ``hdr.frame_id`` at ``hdr.stamp`` into ``target_frame``."""
        translation, rotation = self.lookupTransform(target_frame, hdr.frame_id, hdr.stamp)
        return self.fromTranslationRotation(translation, rotation)

    def fromTranslationRotation(self, translation: Any, rotation: Any) -> np.ndarray:
        """The 4x4 matrix of a translation ``(x, y, z)`` and a rotation ``(x, y, z, w)``."""
        return translation_matrix(translation) @ quaternion_matrix(rotation)

    def _moved(self, target_frame: str, msg: Any, do_transform: Any) -> Any:
        """``msg`` moved into ``target_frame`` at its own stamp, stamped as tf stamps it."""
        header = msg.header
        transform = self._buffer.lookup_transform(_strip(target_frame), _strip(header.frame_id), header.stamp)
        result = do_transform(msg, transform)
        result.header = Header(stamp=header.stamp.model_copy(), frame_id=target_frame)
        return result

    def transformPoint(self, target_frame: str, ps: PointStamped) -> PointStamped:
        """``ps`` in ``target_frame`` (at its own stamp)."""
        return self._moved(target_frame, ps, do_transform_point)  # type: ignore[no-any-return]

    def transformVector3(self, target_frame: str, v3s: Vector3Stamped) -> Vector3Stamped:
        """A direction in ``target_frame`` (rotated only)."""
        return self._moved(target_frame, v3s, do_transform_vector3)  # type: ignore[no-any-return]

    def transformQuaternion(self, target_frame: str, ps: QuaternionStamped) -> QuaternionStamped:
        """An orientation in ``target_frame``."""
        return self._moved(target_frame, ps, do_transform_quaternion)  # type: ignore[no-any-return]

    def transformPose(self, target_frame: str, ps: PoseStamped) -> PoseStamped:
        """``ps`` in ``target_frame`` (at its own stamp)."""
        return self._moved(target_frame, ps, do_transform_pose_stamped)  # type: ignore[no-any-return]


class TransformListener(TransformerROS):
    """A TransformerROS filled from ``/tf`` and ``/tf_static`` (after ``rospy.init_node``)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._listener = Tf2Listener(self._buffer)
        self.setUsingDedicatedThread(True)
