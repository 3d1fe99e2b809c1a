"""roslibpy's action clients against Skydeck's rosbridge endpoint: one scenario per run.

    python roslibpy_actions.py URL SCENARIO

    ros2               roslibpy.ActionClient (ROS 2's send_action_goal ops): /fibonacci, order 5
    ros2_cancel        the same, cancelled after two feedbacks (order 40)
    actionlib          roslibpy.actionlib.ActionClient (ROS 1's topics): /fibonacci, order 5
    actionlib_cancel   the same, cancelled after two feedbacks (order 30)

Prints one JSON object per line for the test to check. Exit 0 when the scenario ran.
"""

from __future__ import annotations

import json
import sys
import threading
import time

import roslibpy
from roslibpy.ros1.actionlib import ActionClient as ActionlibClient
from roslibpy.ros1.actionlib import Goal as ActionlibGoal

TIMEOUT_S = 30


def emit(**values: object) -> None:
    print(json.dumps(values), flush=True)


def ros2(ros: roslibpy.Ros, cancel_after: int | None = None) -> None:
    client = roslibpy.ActionClient(ros, "/fibonacci", "example_interfaces/action/Fibonacci")
    feedback: list[list[int]] = []
    done = threading.Event()
    goal_id = None

    def on_feedback(message: dict) -> None:
        feedback.append(message["sequence"])
        if cancel_after is not None and len(feedback) == cancel_after:
            client.cancel_goal(goal_id)

    def on_result(result: dict) -> None:
        emit(result=result["values"], status=result["status"].name, feedback=feedback)
        done.set()

    def on_error(error: dict) -> None:
        emit(error=error["values"], status=error["status"].name)
        done.set()

    goal_id = client.send_goal(roslibpy.Goal({"order": 40 if cancel_after else 5}), on_result, on_feedback, on_error)
    if not done.wait(TIMEOUT_S):
        raise SystemExit("no action_result")


def actionlib(ros: roslibpy.Ros, cancel_after: int | None = None) -> None:
    client = ActionlibClient(ros, "/fibonacci", "actionlib_tutorials/FibonacciAction")
    goal = ActionlibGoal(client, roslibpy.Message({"order": 30 if cancel_after else 5}))
    feedback: list[list[int]] = []
    statuses: list[int] = []

    def on_feedback(message: dict) -> None:
        feedback.append(message["sequence"])
        if cancel_after is not None and len(feedback) == cancel_after:
            goal.cancel()

    goal.on("feedback", on_feedback)
    goal.on("status", lambda status: statuses.append(status["status"]))
    goal.send()
    result = goal.wait(TIMEOUT_S)
    # The result topic may come before the status topic says the goal ended (two topics, as in
    # ROS 1): its final status follows on /fibonacci/status.
    deadline = time.monotonic() + TIMEOUT_S
    while goal.status["status"] in (0, 1, 6, 7) and time.monotonic() < deadline:
        time.sleep(0.01)
    emit(result=result, status=goal.status["status"], feedback=feedback, statuses=sorted(set(statuses)))
    client.dispose()


def main() -> None:
    url, scenario = sys.argv[1], sys.argv[2]
    ros = roslibpy.Ros(url)
    ros.run(timeout=15)
    emit(connected=ros.is_connected)
    try:
        {
            "ros2": lambda: ros2(ros),
            "ros2_cancel": lambda: ros2(ros, cancel_after=2),
            "actionlib": lambda: actionlib(ros),
            "actionlib_cancel": lambda: actionlib(ros, cancel_after=2),
        }[scenario]()
    finally:
        ros.terminate()


if __name__ == "__main__":
    main()
