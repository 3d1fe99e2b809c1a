"""The bridge: one event-loop thread per process, reached safely from the program's threads."""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable, Iterator

import pytest

from services.ros.bridge import Bridge
from services.runtime.errors import NodeError

pytestmark = pytest.mark.timeout(30)


@pytest.fixture
def bridge() -> Iterator[Bridge]:
    instance = Bridge()
    yield instance
    instance.shutdown()


def test_run_waits_for_a_coroutine_on_the_loop_thread(bridge: Bridge) -> None:
    async def where() -> str:
        await asyncio.sleep(0)
        return threading.current_thread().name

    assert bridge.run(where()) == "skydeck ros bridge"
    assert threading.current_thread().name != "skydeck ros bridge"


def test_run_times_out_and_raises_the_coroutines_error(bridge: Bridge) -> None:
    with pytest.raises(TimeoutError, match="no result within 0.05 s"):
        bridge.run(asyncio.sleep(10), timeout_s=0.05)

    async def fail() -> None:
        raise ValueError("bad")

    with pytest.raises(ValueError, match="bad"):
        bridge.run(fail())


def test_call_runs_on_the_loop_and_call_soon_from_many_threads_keeps_every_item(bridge: Bridge) -> None:
    assert bridge.call(lambda: bridge.in_loop_thread()) is True
    seen: list[int] = []
    threads = [threading.Thread(target=lambda i=i: [bridge.call_soon(seen.append, i * 100 + k) for k in range(100)]) for i in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    bridge.call(lambda: None)  # everything queued before this has run
    assert sorted(seen) == list(range(400))


def test_a_blocking_run_from_the_loop_thread_is_refused_not_a_deadlock(bridge: Bridge) -> None:
    async def inner() -> None:
        pass

    with pytest.raises(NodeError, match="blocking ROS call was made on Skydeck's event loop thread"):
        bridge.call(lambda: bridge.run(inner()))


def test_hand_off_runs_the_callback_where_the_dispatch_says(bridge: Bridge) -> None:
    def dispatch_in_a_thread(job: Callable[[], None]) -> None:
        threading.Thread(target=job, name="worker").start()

    async def ask() -> str:
        return await Bridge.hand_off(dispatch_in_a_thread, lambda: threading.current_thread().name)

    assert bridge.run(ask()) == "worker"

    async def ask_badly() -> None:
        await Bridge.hand_off(dispatch_in_a_thread, lambda: 1 / 0)

    with pytest.raises(ZeroDivisionError):
        bridge.run(ask_badly())


def test_shutdown_stops_the_thread_and_a_new_use_starts_another(bridge: Bridge) -> None:
    first = bridge.loop
    bridge.shutdown()
    assert first.is_closed()
    assert bridge.run(asyncio.sleep(0, result=5)) == 5
