"""ROS 2 actions in the SDK: the goal state machine, the names in a graph, and a server and
client on real nodes against a real core (cancel rules, results kept and expired, status)."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from services.runtime import Node
from services.runtime.actions import (
    ActionClient,
    ActionNames,
    ActionServer,
    GoalEvent,
    GoalStatusCode,
    GoalTransitionError,
    NodeTransport,
    ServerGoal,
    actions_in_graph,
)
from services.runtime.actions.goals import next_status
from shared_models import get_interface
from tests.conftest import wait_until

Fibonacci: Any = get_interface("example_interfaces/action/Fibonacci")
CancelGoal: Any = get_interface("action_msgs/srv/CancelGoal")
S = GoalStatusCode


# -- the state machine and the names (no I/O) ---------------------------------------------------


@pytest.mark.parametrize(
    ("status", "event", "following"),
    [
        (S.ACCEPTED, GoalEvent.EXECUTE, S.EXECUTING),
        (S.ACCEPTED, GoalEvent.CANCEL_GOAL, S.CANCELING),
        (S.EXECUTING, GoalEvent.CANCEL_GOAL, S.CANCELING),
        (S.EXECUTING, GoalEvent.SUCCEED, S.SUCCEEDED),
        (S.EXECUTING, GoalEvent.ABORT, S.ABORTED),
        (S.CANCELING, GoalEvent.SUCCEED, S.SUCCEEDED),
        (S.CANCELING, GoalEvent.ABORT, S.ABORTED),
        (S.CANCELING, GoalEvent.CANCELED, S.CANCELED),
    ],
)
def test_the_transitions_ros2_allows(status: int, event: GoalEvent, following: int) -> None:
    assert next_status(status, event) == following


@pytest.mark.parametrize(
    ("status", "event"),
    [
        (S.ACCEPTED, GoalEvent.SUCCEED),  # a goal must execute before it ends
        (S.ACCEPTED, GoalEvent.CANCELED),
        (S.EXECUTING, GoalEvent.CANCELED),  # nobody asked to cancel it
        (S.EXECUTING, GoalEvent.EXECUTE),
        (S.SUCCEEDED, GoalEvent.ABORT),  # ended is ended
        (S.CANCELED, GoalEvent.CANCEL_GOAL),
    ],
)
def test_every_other_move_is_refused_in_rcls_words(status: int, event: GoalEvent) -> None:
    with pytest.raises(GoalTransitionError, match=f"goal_handle attempted invalid transition from state .* with event {event.name}"):
        next_status(status, event)


def test_an_action_is_found_in_a_graph_by_its_parts() -> None:
    names = ActionNames("/robot1/fibonacci")
    assert (names.send_goal, names.cancel_goal, names.get_result, names.feedback, names.status) == (
        "/robot1/fibonacci/_action/send_goal", "/robot1/fibonacci/_action/cancel_goal",
        "/robot1/fibonacci/_action/get_result", "/robot1/fibonacci/_action/feedback", "/robot1/fibonacci/_action/status",
    )  # fmt: skip
    graph = {
        "services": [
            {"name": "/robot1/fibonacci/_action/send_goal", "type": "example_interfaces/action/Fibonacci_SendGoal", "node": "/server"},
            {"name": "/robot1/fibonacci/_action/get_result", "type": "example_interfaces/action/Fibonacci_GetResult", "node": "/server"},
            {"name": "/take_off", "type": "std_srvs/srv/Trigger", "node": "/control"},
            {"name": "/x/_action/send_goal/deeper", "type": "std_srvs/srv/Trigger", "node": "/odd"},
        ],
        "topics": [
            {"name": "/robot1/fibonacci/_action/feedback", "subscribers": ["/client", "/skydeck_core"]},
            {"name": "/other/_action/feedback", "subscribers": ["/lonely"]},  # no server: no action
        ],
    }
    found = actions_in_graph(graph)
    assert list(found) == ["/robot1/fibonacci"]
    action = found["/robot1/fibonacci"]
    assert (action.type, action.servers, action.clients) == ("example_interfaces/action/Fibonacci", ["/server"], ["/client", "/skydeck_core"])


# -- a server and a client on nodes --------------------------------------------------------------


class Server(Node):
    """An action server whose policy the test sets; goals wait until the test ends them."""

    def __init__(self, settings: Any, *, result_timeout_s: float = 10.0) -> None:
        super().__init__("fib_server", settings=settings)
        self.accept = True
        self.agree_to_cancel = True
        self.accepted: list[ServerGoal] = []
        self.server = ActionServer(
            self, Fibonacci, "fibonacci", on_goal=self._on_goal, on_cancel=self._on_cancel,
            on_accepted=self._on_accepted, result_timeout_s=result_timeout_s,
        )  # fmt: skip

    async def _on_goal(self, goal: Any) -> bool:
        return self.accept and goal.order > 0

    async def _on_cancel(self, goal: ServerGoal) -> bool:
        return self.agree_to_cancel

    def _on_accepted(self, goal: ServerGoal) -> None:
        goal.execute()
        self.accepted.append(goal)


async def _pair(start_node: Any, **server_options: Any) -> tuple[Server, ActionClient, Node]:
    server = await start_node(lambda settings: Server(settings, **server_options))
    client_node = await start_node(lambda settings: Node("fib_client", settings=settings))
    client = ActionClient(NodeTransport(client_node), Fibonacci, "/fibonacci")
    assert await client.wait_for_server(timeout_s=10)
    return server, client, client_node


async def test_feedback_then_the_result_with_the_status_on_the_way(core: Any, start_node: Any) -> None:
    server, client, _ = await _pair(start_node)
    feedback: list[list[int]] = []
    statuses: list[int] = []
    goal = await client.send_goal(
        Fibonacci.Goal(order=3), on_feedback=lambda m: feedback.append(list(m.feedback.sequence)),
        on_status=lambda g: statuses.append(g.status),
    )  # fmt: skip
    assert goal.accepted and goal.stamp.to_nsec() > 0
    result = asyncio.ensure_future(client.get_result(goal))
    await wait_until(lambda: len(server.accepted) == 1, what="the goal to reach the server")
    served = server.accepted[0]
    served.publish_feedback(Fibonacci.Feedback(sequence=[0, 1, 1]))
    served.publish_feedback(Fibonacci.Feedback(sequence=[0, 1, 1, 2]))
    await wait_until(lambda: len(feedback) == 2, what="two feedbacks")
    assert not result.done()  # get_result waits for the result, as ROS 2's does
    served.update(GoalEvent.SUCCEED)
    served.finish(Fibonacci.Result(sequence=[0, 1, 1, 2]))
    response = await asyncio.wait_for(result, 10)
    assert (response.status, response.result.sequence) == (S.SUCCEEDED, [0, 1, 1, 2])
    assert feedback == [[0, 1, 1], [0, 1, 1, 2]]
    assert statuses[-1] == S.SUCCEEDED and S.EXECUTING in statuses
    # A second get_result answers at once from what the server keeps.
    again = await asyncio.wait_for(client.get_result(goal), 5)
    assert again.result.sequence == [0, 1, 1, 2]


async def test_refused_and_duplicate_goals(core: Any, start_node: Any) -> None:
    server, client, _ = await _pair(start_node)
    refused = await client.send_goal(Fibonacci.Goal(order=0))
    assert not refused.accepted and refused.stamp.to_nsec() == 0
    first = await client.send_goal(Fibonacci.Goal(order=5), goal_id=bytes(range(16)))
    again = await client.send_goal(Fibonacci.Goal(order=5), goal_id=bytes(range(16)))  # an ID it holds
    assert first.accepted and not again.accepted
    assert len(server.accepted) == 1
    with pytest.raises(TypeError, match="takes example_interfaces/action/Fibonacci goals"):
        await client.send_goal(Fibonacci.Result())


async def test_cancel_rules_are_rcl_actions(core: Any, start_node: Any) -> None:
    server, client, _ = await _pair(start_node)
    codes = CancelGoal.Response
    unknown = await client.cancel(await _unsent(client))
    assert unknown.return_code == codes.ERROR_UNKNOWN_GOAL_ID and unknown.goals_canceling == []

    one, two = [await client.send_goal(Fibonacci.Goal(order=n)) for n in (3, 4)]
    await wait_until(lambda: len(server.accepted) == 2, what="two goals")
    server.agree_to_cancel = False
    refused = await client.cancel(one)
    assert refused.return_code == codes.ERROR_REJECTED and server.accepted[0].status == S.EXECUTING
    server.agree_to_cancel = True
    agreed = await client.cancel(one)
    assert agreed.return_code == codes.ERROR_NONE and [bytes(g.goal_id.uuid) for g in agreed.goals_canceling] == [one.goal_id]
    assert server.accepted[0].status == S.CANCELING
    twice = await client.cancel(one)  # already cancelling: rcl calls it terminated
    assert twice.return_code == codes.ERROR_GOAL_TERMINATED

    everything = await client.cancel(None)  # zero ID and stamp: every goal still cancelable
    assert [bytes(g.goal_id.uuid) for g in everything.goals_canceling] == [two.goal_id]
    for goal in server.accepted:
        goal.update(GoalEvent.CANCELED)
        goal.finish(Fibonacci.Result())
    ended = await client.cancel(two)
    assert ended.return_code == codes.ERROR_GOAL_TERMINATED
    assert (await client.get_result(one)).status == S.CANCELED


async def test_cancel_by_stamp_takes_the_goals_accepted_until_then(core: Any, start_node: Any) -> None:
    server, client, _ = await _pair(start_node)
    early = await client.send_goal(Fibonacci.Goal(order=3))
    late = await client.send_goal(Fibonacci.Goal(order=3))
    await wait_until(lambda: len(server.accepted) == 2, what="two goals")
    request = CancelGoal.Request()
    request.goal_info.stamp = early.stamp
    response = await client._transport.call(client.names.cancel_goal, CancelGoal, request, 5.0)
    assert [bytes(g.goal_id.uuid) for g in response.goals_canceling] == [early.goal_id]
    assert [g.status for g in server.accepted] == [S.CANCELING, S.EXECUTING]
    assert late.accepted


async def test_a_goal_left_active_is_aborted_and_results_expire(core: Any, start_node: Any) -> None:
    server, client, _ = await _pair(start_node, result_timeout_s=0.3)
    goal = await client.send_goal(Fibonacci.Goal(order=2))
    await wait_until(lambda: len(server.accepted) == 1, what="the goal")
    assert server.accepted[0].finish(Fibonacci.Result(sequence=[7])) is True  # still executing: aborted
    response = await client.get_result(goal)
    assert (response.status, response.result.sequence) == (S.ABORTED, [7])
    await wait_until(lambda: not server.server.goals, what="the result to expire")
    forgotten = await client.get_result(goal)
    assert forgotten.status == S.UNKNOWN and forgotten.result.sequence == []
    with pytest.raises(GoalTransitionError):
        server.accepted[0].update(GoalEvent.SUCCEED)


async def test_the_status_array_lists_every_goal_held_and_is_latched(core: Any, start_node: Any) -> None:
    server, client, client_node = await _pair(start_node)
    goals = [await client.send_goal(Fibonacci.Goal(order=n)) for n in (1, 2)]
    await wait_until(lambda: len(server.accepted) == 2, what="two goals")
    server.accepted[0].update(GoalEvent.SUCCEED)
    latest = server.server.status_publisher._endpoint.latest_frame  # what a late subscriber gets first
    assert latest is not None
    array = get_interface("action_msgs/msg/GoalStatusArray").model_validate_json(latest)
    assert [(bytes(s.goal_info.goal_id.uuid), s.status) for s in array.status_list] == [
        (goals[0].goal_id, S.SUCCEEDED), (goals[1].goal_id, S.EXECUTING)]  # fmt: skip
    await wait_until(lambda: goals[0].status == S.SUCCEEDED, what="the client to see it")


async def test_a_client_waits_for_a_server_that_is_not_there(core: Any, start_node: Any) -> None:
    node = await start_node(lambda settings: Node("lonely", settings=settings))
    client = ActionClient(NodeTransport(node), Fibonacci, "/nobody")
    assert not await client.server_is_ready()
    assert await client.wait_for_server(timeout_s=0.3) is False
    with pytest.raises(TypeError, match="needs an action type"):
        ActionClient(NodeTransport(node), get_interface("std_srvs/srv/Trigger"), "/x")  # type: ignore[arg-type]


async def _unsent(client: ActionClient) -> Any:
    from services.runtime.actions.client import ClientGoal

    return ClientGoal(bytes([9] * 16), None, None)
