"""roslibpy's TF client, parameters and one-connection topic round trip against Skydeck's rosbridge
endpoint: one scenario per run.

    python roslibpy_round_trips.py URL SCENARIO

    tf       roslibpy.tf.TFClient (the republish_tfs service, then its topic): the carrot and
             the post in the world frame, until the carrot has moved
    params   roslibpy.Param: an unset parameter, set, get, a namespace, delete
    echo     one connection subscribes to a topic and publishes on it: its own messages come back

Prints one JSON object per line for the test to check. Exit 0 when the scenario ran.
"""

from __future__ import annotations

import json
import sys
import threading
import time

import roslibpy
from roslibpy.tf import TFClient

TIMEOUT_S = 20


def emit(**values: object) -> None:
    print(json.dumps(values), flush=True)


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
    if not moved.wait(TIMEOUT_S):
        raise SystemExit(f"only {len(carrots)} carrot transforms in {TIMEOUT_S} s")
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
    if not three.wait(TIMEOUT_S):
        raise SystemExit(f"heard {heard} of its own three messages")
    emit(heard=heard)
    listener.unsubscribe()
    chatter.unadvertise()


def main() -> None:
    url, scenario = sys.argv[1], sys.argv[2]
    ros = roslibpy.Ros(url)
    ros.run(timeout=15)
    emit(connected=ros.is_connected)
    try:
        {"tf": tf, "params": params, "echo": echo}[scenario](ros)
    finally:
        ros.terminate()


if __name__ == "__main__":
    main()
