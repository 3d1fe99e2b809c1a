"""One background event loop per process, hosting the SDK's nodes for the ROS façades.

ROS code blocks: ``while rclpy.ok(): rate.sleep()``, ``rospy.spin()``, a service proxy called
from a subscriber's callback, threads of its own. The SDK is asyncio. The bridge keeps the two
apart: every :class:`services.runtime.Node` a façade makes runs on ONE event loop in a daemon
thread (started on first use), and the program's threads talk to it only through here:

- :meth:`Bridge.run` runs a coroutine there and waits for its result (a blocking service call);
- :meth:`Bridge.call` runs a plain function there and waits (creating a subscription on a
  running node touches the loop's state); :meth:`Bridge.call_soon` does not wait (a publish);
- :meth:`Bridge.hand_off` is the other direction: code on the loop (a service request that
  arrived) hands a user callback to the façade's dispatch (rclpy: the executor the program
  spins; rospy: a thread) and awaits its result without blocking the loop.

Called from the loop's own thread, ``call``/``call_soon`` run at once and ``run`` refuses (it
would wait for itself). At interpreter exit the nodes are stopped, so they leave the graph.
"""

from __future__ import annotations

import asyncio
import atexit
import concurrent.futures
import contextlib
import threading
from collections.abc import Callable, Coroutine
from typing import TYPE_CHECKING, Any, TypeVar

from services.runtime.errors import NodeError

if TYPE_CHECKING:
    from services.runtime.node import Node

__all__ = ["Bridge", "bridge"]

T = TypeVar("T")

_STOP_TIMEOUT_S = 5.0


def _new_loop() -> asyncio.AbstractEventLoop:
    try:
        import uvloop
    except ImportError:
        return asyncio.new_event_loop()
    return uvloop.new_event_loop()  # as every Skydeck process (services.runtime.executor.run)


class Bridge:
    """The event-loop thread of this process and the nodes it hosts (see the module docstring)."""

    def __init__(self) -> None:
        self._loop: asyncio.AbstractEventLoop | None = None
        self._thread: threading.Thread | None = None
        self._lock = threading.Lock()
        self._shutting_down = threading.Lock()  # one shutdown at a time; a second waits for it
        self._nodes: list[Node] = []

    # -- the loop -----------------------------------------------------------------------------

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        """The loop, started on first use."""
        loop = self._loop
        if loop is not None:
            return loop
        with self._lock:
            if self._loop is None:
                started = threading.Event()
                loop = _new_loop()
                self._thread = threading.Thread(
                    target=self._serve, args=(loop, started), name="skydeck ros bridge", daemon=True
                )
                self._thread.start()
                started.wait()
                self._loop = loop
                atexit.register(self.shutdown)
            return self._loop

    @staticmethod
    def _serve(loop: asyncio.AbstractEventLoop, started: threading.Event) -> None:
        asyncio.set_event_loop(loop)
        loop.call_soon(started.set)
        loop.run_forever()

    def in_loop_thread(self) -> bool:
        """Whether the caller runs on the loop's thread (a callback the SDK called directly)."""
        return self._thread is not None and threading.current_thread() is self._thread

    # -- program thread -> loop ---------------------------------------------------------------

    def submit(self, coroutine: Coroutine[Any, Any, T]) -> concurrent.futures.Future[T]:
        """Start ``coroutine`` on the loop; its result is the returned future's."""
        return asyncio.run_coroutine_threadsafe(coroutine, self.loop)

    def run(self, coroutine: Coroutine[Any, Any, T], timeout_s: float | None = None) -> T:
        """Run ``coroutine`` on the loop and wait for its result (TimeoutError after ``timeout_s``)."""
        if self.in_loop_thread():
            coroutine.close()
            raise NodeError(
                "a blocking ROS call was made on Skydeck's event loop thread; make it from a "
                "callback the executor runs, or from the program's own thread"
            )
        future = self.submit(coroutine)
        try:
            return future.result(timeout_s)
        except concurrent.futures.TimeoutError:
            future.cancel()
            raise TimeoutError(f"no result within {timeout_s:g} s") from None

    def call(self, function: Callable[..., T], *args: Any) -> T:
        """Run ``function(*args)`` on the loop's thread and return its result (or raise its error)."""
        if self.in_loop_thread():
            return function(*args)
        future: concurrent.futures.Future[T] = concurrent.futures.Future()

        def run() -> None:
            try:
                future.set_result(function(*args))
            except BaseException as error:  # handed to the caller, who raises it
                future.set_exception(error)

        self.loop.call_soon_threadsafe(run)
        return future.result()

    def call_soon(self, function: Callable[..., Any], *args: Any) -> None:
        """Run ``function(*args)`` on the loop's thread, without waiting (at once if already there)."""
        if self.in_loop_thread():
            function(*args)
        else:
            self.loop.call_soon_threadsafe(function, *args)

    # -- loop -> the façade's dispatch --------------------------------------------------------

    @staticmethod
    async def hand_off(dispatch: Callable[[Callable[[], None]], None], function: Callable[[], T]) -> T:
        """Have ``dispatch`` run ``function()`` wherever the façade runs callbacks, and await its
        result on the loop without blocking it (its exception is raised here)."""
        future: concurrent.futures.Future[T] = concurrent.futures.Future()

        def job() -> None:
            if not future.set_running_or_notify_cancel():
                return
            try:
                future.set_result(function())
            except BaseException as error:
                future.set_exception(error)

        dispatch(job)
        return await asyncio.wrap_future(future)

    # -- nodes --------------------------------------------------------------------------------

    def start_node(self, node: Node) -> None:
        """Serve ``node`` and register it with the core (returns once it serves)."""
        self.run(node.start())
        with self._lock:
            self._nodes.append(node)

    def stop_node(self, node: Node) -> None:
        """Stop ``node`` (it leaves the graph); idempotent."""
        with self._lock:
            if node not in self._nodes:
                return
            self._nodes.remove(node)
        node.destroy_node()
        if self._loop is not None and not self.in_loop_thread():
            # On timeout the process is ending anyway; the core drops a node whose session closes.
            with contextlib.suppress(TimeoutError, concurrent.futures.CancelledError):
                self.run(node.stop(), timeout_s=_STOP_TIMEOUT_S)

    @property
    def nodes(self) -> list[Node]:
        with self._lock:
            return list(self._nodes)

    def shutdown(self) -> None:
        """Stop every node and the loop (at interpreter exit, or by the façade's shutdown)."""
        with self._shutting_down:
            self._shutdown()

    def _shutdown(self) -> None:
        for node in reversed(self.nodes):
            self.stop_node(node)
        with self._lock:
            loop, thread = self._loop, self._thread
            self._loop = self._thread = None
        if loop is not None and thread is not None and threading.current_thread() is not thread:
            with contextlib.suppress(TimeoutError, concurrent.futures.TimeoutError, RuntimeError):
                asyncio.run_coroutine_threadsafe(_cancel_the_rest(), loop).result(_STOP_TIMEOUT_S)
            loop.call_soon_threadsafe(loop.stop)
            thread.join(_STOP_TIMEOUT_S)
            if not thread.is_alive():
                loop.close()


async def _cancel_the_rest() -> None:
    """End the tasks the stopped nodes left (keepalives of closing sockets) before the loop stops."""
    tasks = [t for t in asyncio.all_tasks() if t is not asyncio.current_task()]
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)


bridge = Bridge()
"""The process's bridge: every façade node runs on its loop."""
