"""``tf2_ros.Buffer``: tf2's buffer with waiting, async waits and ``transform(msg, frame)``.

    buffer = Buffer()                                   # ROS 2: Buffer(cache_time=None, node=None)
    listener = TransformListener(buffer, node)          # ROS 1: Buffer(cache_time=None, debug=True)
    t = buffer.lookup_transform('odom', 'base_link', Time(), timeout=Duration(seconds=1.0))

``lookup_transform(target, source, time, timeout)`` waits up to ``timeout`` for the transform to
become possible, then looks it up: what it raises after the wait is what it would have raised at
once (a LookupException for a frame never heard of, an ExtrapolationException for a time outside
the data), as tf2_ros's Python Buffer does. Timeouts are wall-clock seconds.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import services.ros.tf2_ros.do_transform  # noqa: F401  (registers geometry_msgs' transforms)
from services.ros.bridge import bridge
from services.ros.rclpy.task import Future
from services.ros.tf2_ros.buffer_core import BufferCore
from services.ros.tf2_ros.buffer_interface import TransformRegistration, TypeException
from services.ros.tf2_ros.exceptions import TransformException
from services.ros.tf2_ros.times import duration_ns, time_ns
from shared_models.geometry_msgs import TransformStamped

__all__ = ["Buffer"]


class Buffer(BufferCore):
    """The buffer a TransformListener fills (see the module docstring)."""

    def __init__(self, cache_time: Any = None, node: Any = None, debug: bool = True) -> None:
        super().__init__(cache_time)
        if isinstance(node, bool):  # ROS 1's Buffer(cache_time, debug)
            node = None
        # Where done callbacks of wait_for_transform_async's futures run: the node's executor.
        self._dispatch: Callable[[Callable[[], None]], None] | None = getattr(node, "_rclpy_dispatch", None)
        self.registration = TransformRegistration()

    # -- waiting lookups --------------------------------------------------------------------

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> TransformStamped:
        """The transform from ``source_frame`` into ``target_frame`` at ``time`` (``Time()``: the
        latest), waiting up to ``timeout`` for it."""
        time_value = time_ns(time)
        self._wait(lambda: self._can(target_frame, source_frame, time_value, "canTransform")[0], timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    def lookup_transform_full(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str,
        timeout: Any = None,
    ) -> TransformStamped:  # fmt: skip
        """``source_frame`` at ``source_time`` into ``target_frame`` at ``target_time`` through
        ``fixed_frame``, waiting up to ``timeout``."""
        if duration_ns(timeout) > 0:
            self.can_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        return self.lookup_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)

    def can_transform(
        self, target_frame: str, source_frame: str, time: Any, timeout: Any = None, return_debug_tuple: bool = False
    ) -> Any:
        """Whether the transform can be had, waiting up to ``timeout`` for it; with
        ``return_debug_tuple``, ``(bool, tf2's reason)``."""
        time_value = time_ns(time)
        self._wait(lambda: self._can(target_frame, source_frame, time_value, "canTransform")[0], timeout)
        result = self.can_transform_core(target_frame, source_frame, time)
        return result if return_debug_tuple else result[0]

    def can_transform_full(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str,
        timeout: Any = None, return_debug_tuple: bool = False,
    ) -> Any:  # fmt: skip
        """:meth:`can_transform` of the advanced API."""
        target_ns, source_ns = time_ns(target_time, "target_time"), time_ns(source_time, "source_time")

        def ready() -> bool:
            return (
                self._can(target_frame, fixed_frame, target_ns, "canTransform")[0]
                and self._can(fixed_frame, source_frame, source_ns, "canTransform")[0]
            )

        self._wait(ready, timeout)
        result = self.can_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)
        return result if return_debug_tuple else result[0]

    def _wait(self, ready: Callable[[], bool], timeout: Any) -> None:
        # Threads vs the event loop: the listener's subscriptions fill this buffer on Skydeck's
        # event loop, never through the executor, so a wait here blocks only the calling thread
        # while data keeps arriving. A lookup with a timeout works from the main thread and from
        # any callback, even under a SingleThreadedExecutor (where rclpy's buffer, filled by the
        # executor the wait blocks, would wait its whole timeout for nothing). On the loop's own
        # thread nothing may block: there it does not wait.
        timeout_s = duration_ns(timeout) / 1e9
        if timeout_s > 0.0 and not bridge.in_loop_thread():
            self._wait_for(ready, timeout_s)

    # -- async waits (rclpy) ----------------------------------------------------------------

    def wait_for_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Future:
        """A Future done with the transform once it can be had (``await`` it in a callback, or
        ``rclpy.spin_until_future_complete(node, future)``)."""
        time_ns(time)
        return self._future(
            lambda: self.can_transform_core(target_frame, source_frame, time)[0],
            lambda: self.lookup_transform_core(target_frame, source_frame, time),
        )

    def wait_for_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> Future:
        """:meth:`wait_for_transform_async` of the advanced API."""
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        return self._future(lambda: self.can_transform_full_core(*args)[0], lambda: self.lookup_transform_full_core(*args))

    async def lookup_transform_async(self, target_frame: str, source_frame: str, time: Any) -> TransformStamped:
        """``await buffer.lookup_transform_async('odom', 'base_link', Time())`` in an async callback."""
        await self.wait_for_transform_async(target_frame, source_frame, time)
        return self.lookup_transform_core(target_frame, source_frame, time)

    async def lookup_transform_full_async(
        self, target_frame: str, target_time: Any, source_frame: str, source_time: Any, fixed_frame: str
    ) -> TransformStamped:
        await self.wait_for_transform_full_async(target_frame, target_time, source_frame, source_time, fixed_frame)
        return self.lookup_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)

    def _future(self, possible: Callable[[], bool], lookup: Callable[[], TransformStamped]) -> Future:
        future = Future()
        future._dispatch = self._dispatch

        def check() -> None:
            if future.done():
                self._remove_new_data_callback(check)
                return
            if not possible():
                return
            self._remove_new_data_callback(check)
            try:
                future.set_result(lookup())
            except TransformException as error:
                future.set_exception(error)

        self._add_new_data_callback(check)
        check()  # after adding it, so data arriving in between is not missed
        return future

    # -- messages ---------------------------------------------------------------------------

    def transform(self, object_stamped: Any, target_frame: str, timeout: Any = None, new_type: Any = None) -> Any:
        """``object_stamped`` (a PointStamped, PoseStamped, ...) in ``target_frame``, at its own
        stamp (a zero stamp: the latest), waiting up to ``timeout``."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        transform = self.lookup_transform(target_frame, header.frame_id, header.stamp, timeout)
        return _as(do_transform(object_stamped, transform), new_type)

    def transform_full(
        self, object_stamped: Any, target_frame: str, target_time: Any, fixed_frame: str, timeout: Any = None,
        new_type: Any = None,
    ) -> Any:  # fmt: skip
        """``object_stamped`` in ``target_frame`` at ``target_time``, through ``fixed_frame``."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        transform = self.lookup_transform_full(
            target_frame, target_time, header.frame_id, header.stamp, fixed_frame, timeout
        )
        return _as(do_transform(object_stamped, transform), new_type)


def _as(result: Any, new_type: Any) -> Any:
    if new_type is None or isinstance(result, new_type):
        return result
    raise TypeException(f"Type {new_type} is not loaded or supported: transform() returns the input's own type")

