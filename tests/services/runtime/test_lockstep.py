"""Lockstep runs (services.runtime.lockstep): what a process waits for, what the coordinator
counts, and a small run of two nodes stepped by hand."""

from __future__ import annotations

import asyncio
import logging

from websockets.asyncio.client import connect

from services.grading.coordinator import Coordinator, _unsettled
from services.runtime import Node, NodeSettings
from services.runtime.clock import Clock
from services.runtime.lockstep import agent as lockstep
from services.runtime.lockstep.frames import HelloFrame, NodeCounts, ReportFrame
from services.runtime.subscription import Subscription
from services.runtime.timer import Timer
from shared_models.builtin_interfaces import Time
from shared_models.std_msgs import Int32
from tests.conftest import CoreProcess, wait_until


def report(settled: bool = True, **nodes: tuple[list[tuple[str, str, int]], list[tuple[str, str, int]]]) -> ReportFrame:
    return ReportFrame(
        id=1,
        settled=settled,
        nodes=[
            NodeCounts(
                name="/" + name,
                sent=sent,
                received=received,
            )
            for name, (sent, received) in nodes.items()
        ],
    )


def test_the_run_has_settled_when_every_message_between_its_nodes_arrived() -> None:
    sim = report(sim=([("/scan", "/me", 3), ("/scan", "/bag", 3)], [("/cmd_vel", "/me", 2)]))
    me = report(me=([("/cmd_vel", "/sim", 2)], [("/scan", "/sim", 3), ("/rosout", "/skydeck_core", 9)]))
    bag = report(bag=([], [("/scan", "/sim", 3)]))
    assert _unsettled([sim, me, bag]) is None  # the core is not in the run: its counts do not matter
    late = report(bag=([], [("/scan", "/sim", 2)]))
    assert _unsettled([sim, me, late]) == "/scan from /sim to /bag: 2 of 3 arrived"
    busy = report(False, me=([], []))
    assert _unsettled([sim, busy, bag]) == "/me: still busy"


async def test_a_timer_on_sim_time_is_busy_from_when_it_is_due_until_its_call_returned() -> None:
    clock = Clock(use_sim_time=True)
    calls: list[float] = []
    entered = asyncio.Event()
    release = asyncio.Event()

    async def callback() -> None:
        calls.append(clock.now_s())
        entered.set()
        await release.wait()

    timer = Timer(0.1, callback, clock)
    task = asyncio.ensure_future(timer.run(logging.getLogger("test")))
    await asyncio.sleep(0)
    assert not timer.busy
    clock.set_sim_time(Time(sec=0, nanosec=50_000_000))
    assert not timer.busy  # not due yet
    clock.set_sim_time(Time(sec=0, nanosec=100_000_000))
    assert timer.busy  # due: the task has not even woken yet
    await entered.wait()
    assert timer.busy  # its call runs
    release.set()
    await wait_until(lambda: not timer.busy, what="the call to end")
    assert calls == [0.1]
    task.cancel()


async def test_a_subscription_is_idle_once_its_queue_is_handled() -> None:
    seen: list[int] = []
    subscription = Subscription("/n", Int32, lambda msg: seen.append(msg.data), 10)
    subscription.enqueue(Int32(data=1))
    assert not subscription.idle
    task = asyncio.ensure_future(subscription.run(logging.getLogger("test")))
    await wait_until(lambda: subscription.idle, what="the message to be handled")
    assert seen == [1]
    task.cancel()


class _World(Node):
    """A stand-in simulator: each step publishes a counter."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("world", settings=settings)
        self.count = 0
        self.publisher = self.create_publisher(Int32, "/count", 10)

    def step(self, what: str) -> float:
        if what == "advance":
            self.count += 1
        self.publisher.publish(Int32(data=self.count))
        return self.count * 0.1


class _Follower(Node):
    """On sim time: a timer that says which count it has seen, at each tenth of a second."""

    def __init__(self, settings: NodeSettings) -> None:
        super().__init__("follower", settings=settings.model_copy(update={"use_sim_time": True}))
        self.latest = -1
        self.ticks: list[tuple[float, int]] = []
        self.create_subscription(Int32, "/count", self.on_count, 10)
        self.create_timer(0.1, self.on_timer)

    def on_count(self, msg: Int32) -> None:
        self.latest = msg.data

    def on_timer(self) -> None:
        self.ticks.append((round(self.get_clock().now().nanoseconds * 1e-9, 3), self.latest))


async def test_a_run_stepped_by_hand_moves_the_clock_only_once_the_step_has_arrived(core: CoreProcess) -> None:
    coordinator = Coordinator(settle_timeout_s=10.0)
    url = await coordinator.start()
    settings = NodeSettings(core_url=core.url, port=0, lockstep_url=url)
    world, follower = _World(settings), _Follower(settings)
    try:
        await world.start()
        lockstep.set_stepper(world.step)
        await follower.start()
        await coordinator.wait_for_processes(1, timeout_s=10.0)
        await wait_until(lambda: bool(follower._participant.links), timeout_s=10.0, what="the follower to link")
        assert await coordinator.settle()
        await coordinator.settle(after=await coordinator.step("start"))
        for _ in range(5):
            await coordinator.settle(after=await coordinator.step("advance"))
        # Each tick the timer saw the count of that very step: the clock moved after it arrived.
        assert follower.ticks == [(0.1, 1), (0.2, 2), (0.3, 3), (0.4, 4), (0.5, 5)]
        assert coordinator.settling.lost == 0
    finally:
        await follower.stop()
        await world.stop()
        await coordinator.stop()


async def test_a_process_that_stops_answering_is_stuck_and_named_by_its_pid() -> None:
    """A process whose event loop is blocked never answers a settle: the coordinator waits no
    longer than the settle (plus a report's own wait) and names it, so the run can stop it."""
    coordinator = Coordinator(settle_timeout_s=0.3)
    url = await coordinator.start()
    try:
        async with connect(url) as silent:
            await silent.send(HelloFrame(pid=424242).model_dump_json())
            assert await coordinator.wait_for_processes(1, timeout_s=10.0)
            settled = await asyncio.wait_for(coordinator.settle(), timeout=30.0)
            assert settled is False
            assert coordinator.settling.stuck == [424242] and coordinator.settling.lost == 1
            assert coordinator.settling.last_reason == "process 424242 did not answer"
            assert await silent.recv()  # it was asked (a settle frame), and never answered
    finally:
        await coordinator.stop()
