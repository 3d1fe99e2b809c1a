"""``rclpy.task.Future``: the result of ``client.call_async(request)``, filled in later.

Thread-safe: the bridge's loop completes it; any thread may wait on it, poll ``done()``, or
``await`` it in an ``async def`` callback. Done callbacks run in the executor the node is spun
by (as rclpy schedules them), or at once where none spins it.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Generator
from typing import Any

__all__ = ["Future"]


class Future:
    """A result to come: ``done()``, ``result()``, ``exception()``, ``add_done_callback(cb)``."""

    def __init__(self, *, executor: Any = None) -> None:
        self._done = threading.Event()
        self._lock = threading.Lock()
        self._result: Any = None
        self._exception: BaseException | None = None
        self._cancelled = False
        self._callbacks: list[Callable[[Future], Any]] = []
        self._wakers: list[Callable[[], None]] = []
        self._dispatch: Callable[[Callable[[], None]], None] | None = None
        self._executor = executor

    def done(self) -> bool:
        return self._done.is_set()

    def cancelled(self) -> bool:
        return self._cancelled

    def result(self) -> Any:
        """The result (None while not done); raises the exception the call ended with."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        return self._exception

    def set_result(self, result: Any) -> None:
        self._finish(result, None)

    def set_exception(self, exception: BaseException) -> None:
        self._finish(None, exception)

    def cancel(self) -> None:
        if not self.done():
            self._cancelled = True
            self._finish(None, None)

    def add_done_callback(self, callback: Callable[[Future], Any]) -> None:
        """Call ``callback(future)`` once done (at once, if it is)."""
        with self._lock:
            if not self.done():
                self._callbacks.append(callback)
                return
        self._schedule(callback)

    def wait(self, timeout_sec: float | None = None) -> bool:
        """Block until done (Skydeck's, for code that waits from a thread); whether it is."""
        return self._done.wait(timeout_sec)

    def __await__(self) -> Generator[Future, None, Any]:
        while not self.done():
            yield self  # the executor's coroutine driver waits for it
        return self.result()

    # -- internals ----------------------------------------------------------------------------

    def _add_waker(self, waker: Callable[[], None]) -> None:
        """``waker()`` when done, in the completing thread (an executor waiting to spin on)."""
        with self._lock:
            if not self.done():
                self._wakers.append(waker)
                return
        waker()

    def _finish(self, result: Any, exception: BaseException | None) -> None:
        with self._lock:
            if self.done():
                return
            self._result, self._exception = result, exception
            self._done.set()
            callbacks, self._callbacks = self._callbacks, []
            wakers, self._wakers = self._wakers, []
        for waker in wakers:
            waker()
        for callback in callbacks:
            self._schedule(callback)

    def _schedule(self, callback: Callable[[Future], Any]) -> None:
        if self._dispatch is not None:
            self._dispatch(lambda: callback(self))
        else:
            callback(self)
