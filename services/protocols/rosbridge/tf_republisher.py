"""tf2_web_republisher, served by the core: what roslibjs's and roslibpy's TF clients ask for.

A browser cannot listen to ``/tf`` itself (every link at the broadcasters' rate), so ROS's
``tf2_web_republisher`` node looks up the frames a client names, in the frame it names, and sends
only those that moved (:mod:`.tf_watch`). The core hosts it as the guest node
``/tf2_web_republisher``, with its three front doors:

- ROS 1's action ``/tf2_web_republisher`` (``tf2_web_republisher/TFSubscriptionAction`` over
  actionlib's topics, :mod:`.actionlib_host`): the goal names the frames, each feedback carries
  the transforms that moved; the goal runs until cancelled. roslibjs's ``ROSLIB.TFClient``.
- ROS 2's action ``/tf2_web_republisher`` (``tf2_web_republisher_interfaces/action/TFSubscription``,
  the SDK's action server): the same, through rosbridge's ``send_action_goal``; a goal with no
  frames, no target or a rate out of range is refused, as ROS 2's node refuses it. roslibjs's
  ``ROSLIB.ROS2TFClient``.
- the service ``/republish_tfs`` (``tf2_web_republisher/RepublishTFs``): the same request with a
  ``timeout``, answered with a topic (``/tf2_web_republisher/tf_repub_N``, latched,
  ``tf2_web_republisher/TFArray``) the client then reads; the topic goes once nobody has read
  it for ``timeout``. roslibpy's ``roslibpy.tf.TFClient``. The JSON is the same for ROS 2's
  ``tf2_web_republisher_interfaces/srv/RepublishTFs``; the service is typed as ROS 1's, whose
  names roslibpy uses.

A goal whose feedback nobody reads for ``UNREAD_GOAL_S`` (its client went without cancelling
it) is ended: aborted, as nobody waits for it.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
from typing import Any

from services.core.access import CoreAccess
from services.protocols.ops import Refused
from services.protocols.rosbridge.actionlib_host import ActionlibHost
from services.protocols.rosbridge.core_host import CoreHost, CorePublisher
from services.protocols.rosbridge.tf_watch import TFRequest, TFSource, Watch
from services.runtime.actions.goals import GoalEvent, GoalStatusCode
from services.runtime.actions.server import ActionServer, ServerGoal
from shared_models import ActionType, Message, ServiceType, get_interface
from shared_models.geometry_msgs import TransformStamped

__all__ = ["NODE", "UNREAD_GOAL_S", "TFRepublisher"]

logger = logging.getLogger("skydeck.rosbridge")

NODE = "/tf2_web_republisher"
UNREAD_GOAL_S = 10.0
_ROS1_ACTION = "tf2_web_republisher/action/TFSubscription"
_ROS2_ACTION = "tf2_web_republisher_interfaces/action/TFSubscription"
_SERVICE = "tf2_web_republisher/srv/RepublishTFs"
_ARRAY = "tf2_web_republisher/msg/TFArray"


class TFRepublisher:
    """The guest ``/tf2_web_republisher`` and its watches (see the module docstring)."""

    def __init__(self, access: CoreAccess) -> None:
        guest = access.guests.add(NODE, client="tf2_web_republisher (answered by the core)")
        self._host = CoreHost(access, guest)
        self._source = TFSource(self._host)
        self._ids = itertools.count()
        self._topics: dict[str, tuple[Watch, CorePublisher]] = {}
        self._ros1_goals: dict[str, Watch] = {}
        self._ros1 = ActionlibHost(self._host, NODE, _ROS1_ACTION, on_goal=self._ros1_goal, on_cancel=self._ros1_cancel)
        self._ros2_goals: dict[bytes, Watch] = {}
        ros2_type = get_interface(_ROS2_ACTION)
        if not (isinstance(ros2_type, type) and issubclass(ros2_type, ActionType)):
            raise TypeError(f"{_ROS2_ACTION} is not an action type")
        self._ros2_type = ros2_type
        self._ros2 = ActionServer(
            self._host, ros2_type, NODE, on_goal=self._ros2_accepts, on_cancel=self._ros2_cancel, on_accepted=self._ros2_run
        )
        service = get_interface(_SERVICE)
        if not (isinstance(service, type) and issubclass(service, ServiceType)):
            raise TypeError(f"{_SERVICE} is not a service type")
        self._service: Any = service
        self._array: Any = get_interface(_ARRAY)
        self._host.create_service(service, "/republish_tfs", self._republish)

    # -- ROS 1's action -------------------------------------------------------------------------

    def _ros1_goal(self, goal_id: str, goal: Any) -> str | None:
        request = TFRequest.of(goal)
        problem = request.problem()
        if problem is not None:
            return problem
        feedback = self._ros1.feedback_type

        def emit(transforms: list[TransformStamped]) -> None:
            self._ros1.publish_feedback(goal_id, feedback(transforms=transforms))

        def abandoned() -> None:
            self._ros1_goals.pop(goal_id, None)
            self._ros1.finish(goal_id, f"nobody read {NODE}/feedback for {UNREAD_GOAL_S:g} s")

        self._ros1_goals[goal_id] = Watch(
            self._source, request, emit, wanted=lambda: self._ros1.feedback_publisher.read,
            unread_s=UNREAD_GOAL_S, on_abandoned=abandoned,
        )  # fmt: skip
        return None

    def _ros1_cancel(self, goal_id: str) -> None:
        watch = self._ros1_goals.pop(goal_id, None)
        if watch is not None:
            watch.stop()

    # -- ROS 2's action -------------------------------------------------------------------------

    async def _ros2_accepts(self, goal: Message) -> bool:
        problem = TFRequest.of(goal).problem()
        if problem is not None:
            logger.warning("%s refused a goal: %s", NODE, problem)
        return problem is None

    def _ros2_run(self, goal: ServerGoal) -> None:
        goal.execute()
        feedback = self._ros2_type.Feedback
        key = goal.goal_id

        def abandoned() -> None:
            self._ros2_goals.pop(key, None)
            goal.finish(self._ros2_type.Result())  # still active: aborted

        self._ros2_goals[key] = Watch(
            self._source, TFRequest.of(goal.request), lambda transforms: goal.publish_feedback(feedback(transforms=transforms)),
            wanted=lambda: self._ros2.feedback_publisher.read, unread_s=UNREAD_GOAL_S, on_abandoned=abandoned,
        )  # fmt: skip

    async def _ros2_cancel(self, goal: ServerGoal) -> bool:
        watch = self._ros2_goals.pop(goal.goal_id, None)
        if watch is not None:
            watch.stop()
        # Once the server has moved it to CANCELING (after this answer), it ends cancelled.
        asyncio.get_running_loop().call_soon(self._ros2_cancelled, goal)
        return True

    def _ros2_cancelled(self, goal: ServerGoal) -> None:
        if goal.status == GoalStatusCode.CANCELING:
            goal.update(GoalEvent.CANCELED)
            goal.finish(self._ros2_type.Result())

    # -- the service ----------------------------------------------------------------------------

    def _republish(self, request: Any) -> Any:
        tf_request = TFRequest.of(request)
        problem = tf_request.problem()
        if problem is not None:
            raise Refused(f"republish_tfs: {problem}")
        topic = f"{NODE}/tf_repub_{next(self._ids)}"
        publisher = self._host.create_publisher(self._array, topic, 10, latched=True)

        def abandoned() -> None:
            self._topics.pop(topic, None)
            self._host.destroy_publisher(publisher)
            logger.info("%s: nobody read %s for %.3g s: the topic is taken down", NODE, topic, timeout_s)

        timeout_s = request.timeout.to_sec()
        watch = Watch(
            self._source, tf_request, lambda transforms: publisher.publish(self._array(transforms=transforms)),
            wanted=lambda: publisher.read, unread_s=timeout_s, on_abandoned=abandoned,
        )  # fmt: skip
        self._topics[topic] = (watch, publisher)
        return self._service.Response(topic_name=topic)

    def close(self) -> None:
        """Every watch ends, and the guest's topics and services with them."""
        for watch in [*self._ros1_goals.values(), *self._ros2_goals.values(), *(w for w, _ in self._topics.values())]:
            watch.stop()
        self._ros1_goals.clear()
        self._ros2_goals.clear()
        self._topics.clear()
        self._ros1.close()
        self._ros2.close()
        self._host.close()
