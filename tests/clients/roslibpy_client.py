"""roslibpy (from PyPI) driving Skydeck's rosbridge endpoint: one scenario per run.

    python roslibpy_client.py URL SCENARIO [TOKEN] [NAMESPACE]

Prints one JSON object per line for the test to check; ``hosted`` waits for a line on stdin
before it ends (the test calls the hosted service meanwhile). Exit 0 when the scenario ran.
Round trips: ``tf`` (roslibpy.tf.TFClient, through the republish_tfs service and its topic),
``params`` (roslibpy.Param on ROS 1 names), ``echo`` (one connection hears its own messages).
"""

from __future__ import annotations

import json
import sys
import threading
import time

import roslibpy
from roslibpy.tf import TFClient

ROUND_TRIP_TIMEOUT_S = 20


def emit(**values: object) -> None:
    print(json.dumps(values), flush=True)


def first_message(ros: roslibpy.Ros, name: str, type_name: str, timeout_s: float = 10.0) -> dict:
    got: list[dict] = []
    ready = threading.Event()
    topic = roslibpy.Topic(ros, name, type_name)

    def received(message: dict) -> None:
        if not got:
            got.append(message)
            ready.set()

    topic.subscribe(received)
    if not ready.wait(timeout_s):
        raise SystemExit(f"no message on {name} within {timeout_s} s")
    topic.unsubscribe()
    return got[0]


def tour(ros: roslibpy.Ros) -> None:
    """What the issue lists: pose, cmd_vel, take_off, get_topics, rosapi without a slash."""
    emit(pose=first_message(ros, "/drone/pose", "geometry_msgs/msg/PoseStamped"))
    emit(latched=first_message(ros, "/drone/name", "std_msgs/msg/String"))
    cmd_vel = roslibpy.Topic(ros, "/drone/cmd_vel", "geometry_msgs/msg/Twist")
    cmd_vel.advertise()
    time.sleep(1.0)  # as with ROS: subscribers connect to a new publisher in a moment
    for x in (0.5, 1.0, 1.5):
        cmd_vel.publish(roslibpy.Message({"linear": {"x": x, "y": 0.0, "z": 0.0}}))
    emit(published=3)
    take_off = roslibpy.Service(ros, "/control/take_off", "std_srvs/srv/Trigger")
    emit(take_off=dict(take_off.call(roslibpy.ServiceRequest(), timeout=10)))
    emit(again=dict(take_off.call(roslibpy.ServiceRequest(), timeout=10)))
    emit(topics=ros.get_topics())
    emit(topic_type=ros.get_topic_type("/drone/pose"))
    emit(services=ros.get_services())
    emit(nodes=ros.get_nodes())
    relative = roslibpy.Service(ros, "rosapi/topics", "rosapi_msgs/srv/Topics")
    emit(relative=dict(relative.call(roslibpy.ServiceRequest(), timeout=10)))
    now = ros.get_time()  # roslibpy reads ROS 1's secs/nsecs
    emit(time={"secs": now.secs, "nsecs": now.nsecs})
    missing = roslibpy.Service(ros, "/no/such/service", "std_srvs/srv/Trigger")
    try:
        missing.call(roslibpy.ServiceRequest(), timeout=10)
        emit(missing="answered?!")
    except Exception as error:  # roslibpy raises ServiceException with the server's reason
        emit(missing=str(error))
    cmd_vel.unadvertise()


def hosted(ros: roslibpy.Ros) -> None:
    """Host /demo/set_light (std_srvs/SetBool) until told to stop."""
    calls: list[dict] = []

    def handler(request: dict, response: dict) -> bool:
        calls.append(dict(request))
        response["success"] = True
        response["message"] = "light " + ("on" if request["data"] else "off")
        emit(served=dict(request))
        return True

    service = roslibpy.Service(ros, "/demo/set_light", "std_srvs/srv/SetBool")
    service.advertise(handler)
    time.sleep(0.5)  # the advertise op travels before the test calls
    emit(advertised="/demo/set_light")
    sys.stdin.readline()
    service.unadvertise()
    emit(calls=len(calls))


ROSAPI_CALLS = [  # the services the issue lists, each with a request that has an answer to check
    ("topics", {}),
    ("topics_for_type", {"type": "geometry_msgs/msg/PoseStamped"}),
    ("services", {}),
    ("service_type", {"service": "/control/take_off"}),
    ("topic_type", {"topic": "/drone/pose"}),
    ("nodes", {}),
    ("node_details", {"node": "/drone"}),
    ("message_details", {"type": "geometry_msgs/msg/PoseStamped"}),
    ("service_request_details", {"type": "std_srvs/srv/SetBool"}),
    ("service_response_details", {"type": "std_srvs/srv/SetBool"}),
    ("get_param", {"name": "/tuned:max_speed"}),
    ("set_param", {"name": "/tuned:retries", "value": "5"}),
    ("get_param_names", {}),
    ("get_time", {}),
]


def rosapi(ros: roslibpy.Ros) -> None:
    """Every rosapi service, called as /rosapi/NAME and as rosapi/NAME; then roslibpy's own helpers."""
    for name, args in ROSAPI_CALLS:
        answers = []
        for spelling in (f"/rosapi/{name}", f"rosapi/{name}"):
            service = roslibpy.Service(ros, spelling, "rosapi/" + name.title().replace("_", ""))
            answers.append(dict(service.call(roslibpy.ServiceRequest(args), timeout=10)))
        emit(rosapi=name, slash=answers[0], relative=answers[1])
    emit(helpers={
        "topics_for_type": ros.get_topics_for_type("geometry_msgs/msg/PoseStamped"),
        "service_type": ros.get_service_type("/control/take_off"),
        "node_details": ros.get_node_details("/drone"),
        "params": ros.get_params(),
        "param": ros.get_param("/tuned:retries"),
        "request_details": dict(ros.get_service_request_details("std_srvs/srv/SetBool")),
        "response_details": dict(ros.get_service_response_details("std_srvs/srv/SetBool")),
    })


def stuck(ros: roslibpy.Ros) -> None:
    """Call /stuck/wait, which never answers, with no timeout in the request: the core's default
    ends it with an error response, which roslibpy raises as ServiceException."""
    service = roslibpy.Service(ros, "/stuck/wait", "std_srvs/srv/Trigger")
    try:
        service.call(roslibpy.ServiceRequest(), timeout=30)  # roslibpy's own wait, not sent
        emit(stuck="answered?!")
    except Exception as error:
        emit(stuck=str(error), kind=type(error).__name__)
    emit(after=ros.get_topic_type("/drone/pose"))  # the connection carries on


def workshop(ros: roslibpy.Ros) -> None:
    """The real workshop system: read the pose, take off, watch the drone climb."""
    emit(pose=first_message(ros, "/drone/pose", "geometry_msgs/msg/PoseStamped"))
    take_off = roslibpy.Service(ros, "/control/take_off", "std_srvs/srv/Trigger")
    emit(take_off=dict(take_off.call(roslibpy.ServiceRequest(), timeout=10)))
    climbed = threading.Event()
    heights: list[float] = []

    def follow(message: dict) -> None:
        heights.append(message["pose"]["position"]["z"])
        if heights[-1] > 2.0:
            climbed.set()

    pose = roslibpy.Topic(ros, "/drone/pose", "geometry_msgs/msg/PoseStamped", throttle_rate=100)
    pose.subscribe(follow)
    emit(climbed=climbed.wait(60), top=max(heights, default=0.0))
    pose.unsubscribe()
    emit(topics=ros.get_topics())


class Statuses:
    """The ``status`` ops the server sends. roslibpy has no handler for them (it raises on one):
    this scenario adds one, as roslibjs has, to see the fences' refusals."""

    def __init__(self, ros: roslibpy.Ros) -> None:
        self.seen: list[dict] = []
        self._arrived = threading.Condition()
        ros.factory.on_ready(lambda proto: proto._message_handlers.__setitem__("status", self._add))
        ros.send_on_ready(roslibpy.Message({"op": "set_level", "level": "info"}))  # a status for every advertise

    def _add(self, message: dict) -> None:
        with self._arrived:
            self.seen.append(dict(message))
            self._arrived.notify_all()

    def about(self, text: str, timeout_s: float = 10.0) -> dict:
        """The first status whose message names ``text`` (waiting for it)."""
        with self._arrived:
            if not self._arrived.wait_for(lambda: any(text in s["msg"] for s in self.seen), timeout_s):
                raise SystemExit(f"no status about {text} within {timeout_s} s: {self.seen}")
            return next(s for s in self.seen if text in s["msg"])


def _call(ros: roslibpy.Ros, name: str, type_name: str, request: dict) -> dict:
    try:
        return {"answer": dict(roslibpy.Service(ros, name, type_name).call(roslibpy.ServiceRequest(request), timeout=10))}
    except Exception as error:  # roslibpy's ServiceException carries the server's reason
        return {"refused": str(error)}


def fences(ros: roslibpy.Ros) -> None:
    """Each verb the fences guard, on the names of the namespace given (argv[4]), as the token
    given (argv[3], or none) may do it: one line per verb, what the server answered."""
    target = sys.argv[4]
    statuses = Statuses(ros)
    scan = f"/{target}/scan"
    got: list[dict] = []
    received = threading.Event()
    topic = roslibpy.Topic(ros, scan, "std_msgs/msg/String")
    topic.subscribe(lambda message: (got.append(message), received.set()))
    said = statuses.about(f"{scan}")  # subscribed (info) or refused (error)
    if said["level"] == "info":
        received.wait(10)
    emit(verb="read", level=said["level"], status=said["msg"], message=got[0] if got else None)
    cmd_vel = roslibpy.Topic(ros, f"/{target}/cmd_vel", "geometry_msgs/msg/Twist")
    cmd_vel.advertise()
    said = statuses.about(f"/{target}/cmd_vel")
    if said["level"] == "info":
        time.sleep(1.0)  # as with ROS: subscribers connect to a new publisher in a moment
        cmd_vel.publish(roslibpy.Message({"linear": {"x": 0.25, "y": 0.0, "z": 0.0}}))
    emit(verb="publish", level=said["level"], status=said["msg"])
    emit(verb="call", **_call(ros, f"/{target}/ping", "std_srvs/srv/Trigger", {}))
    roslibpy.Service(ros, f"/{target}/hosted", "std_srvs/srv/Trigger").advertise(lambda request, response: True)
    said = statuses.about(f"/{target}/hosted")
    emit(verb="serve", level=said["level"], status=said["msg"])
    emit(verb="set_parameter", **_call(
        ros, "/rosapi/set_param", "rosapi_msgs/srv/SetParam", {"name": f"/{target}/driver:gain", "value": "2.5"}
    ))  # fmt: skip
    emit(verb="kill_node", **_call(ros, "/skydeck_launch/kill_node", "skydeck_launch/srv/KillNode", {"node": f"/{target}/driver"}))
    emit(verb="reset_world", **_call(ros, "/simulator/reset", "std_srvs/srv/Trigger", {}))
    # The connection carries on after every refusal: it still answers (what it may not do, too).
    emit(after=_call(ros, "/rosapi/topic_type", "rosapi_msgs/srv/TopicType", {"topic": "/clock"}))


def tf(ros: roslibpy.Ros) -> None:
    client = TFClient(ros, fixed_frame="/world", angular_threshold=0.01, translation_threshold=0.01, rate=20.0)
    carrots: list[dict] = []
    posts: list[dict] = []
    moved = threading.Event()

    def on_carrot(transform: dict) -> None:
        carrots.append(transform)
        if len(carrots) >= 5:
            moved.set()

    client.subscribe("carrot", on_carrot)
    client.subscribe("/post", posts.append)
    if not moved.wait(ROUND_TRIP_TIMEOUT_S):
        raise SystemExit(f"only {len(carrots)} carrot transforms in {ROUND_TRIP_TIMEOUT_S} s")
    emit(carrots=carrots[:5], posts=posts, topic=client.current_topic.name)
    client.dispose()


def params(ros: roslibpy.Ros) -> None:
    speed = roslibpy.Param(ros, "/robot/max_speed")
    emit(unset=speed.get(timeout=10))
    speed.set(1.5, timeout=10)
    emit(set=speed.get(timeout=10))
    roslibpy.Param(ros, "/robot/name").set("neato", timeout=10)
    emit(namespace=roslibpy.Param(ros, "/robot").get(timeout=10))
    emit(names=[name for name in ros.get_params() if name.startswith("/robot/")])
    speed.delete(timeout=10)
    emit(deleted=speed.get(timeout=10))


def echo(ros: roslibpy.Ros) -> None:
    # Two Topic objects (one connection): roslibpy's unsubscribe and unadvertise on one object
    # both remove its reconnect handler, and the second raises KeyError (roslibpy 2.1's own bug).
    listener = roslibpy.Topic(ros, "/chatter", "std_msgs/msg/String")
    chatter = roslibpy.Topic(ros, "/chatter", "std_msgs/msg/String")
    heard: list[str] = []
    three = threading.Event()

    def hear(message: dict) -> None:
        heard.append(message["data"])
        if len(heard) == 3:
            three.set()

    listener.subscribe(hear)
    chatter.advertise()
    time.sleep(0.5)  # as with ROS: the subscription links to the new publisher in a moment
    for n in range(3):
        chatter.publish(roslibpy.Message({"data": f"hello {n}"}))
    if not three.wait(ROUND_TRIP_TIMEOUT_S):
        raise SystemExit(f"heard {heard} of its own three messages")
    emit(heard=heard)
    listener.unsubscribe()
    chatter.unadvertise()


def main() -> None:
    url, scenario = sys.argv[1], sys.argv[2]
    headers = {"Authorization": f"Bearer {sys.argv[3]}"} if len(sys.argv) > 3 and sys.argv[3] else None
    ros = roslibpy.Ros(url, headers=headers)
    ros.run(timeout=15)
    emit(connected=ros.is_connected)
    try:
        scenarios = {"tour": tour, "hosted": hosted, "rosapi": rosapi, "stuck": stuck, "workshop": workshop,
                     "fences": fences, "tf": tf, "params": params, "echo": echo}  # fmt: skip
        scenarios[scenario](ros)
    finally:
        ros.terminate()


if __name__ == "__main__":
    main()
