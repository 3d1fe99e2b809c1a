"""One end of a ROS 2 bridge measurement: an rclpy or a Skydeck publisher or subscriber.

    python -m benchmarks.ros2_worker rclpy-sub /bench/ros2 --duration 3
    python -m benchmarks.ros2_worker skydeck-pub /bench/ros2 --rate 0 --duration 6

Messages are ``geometry_msgs/PointStamped`` (small) or, with ``--image``, a 640x480 rgb8
``sensor_msgs/Image``; each carries its send time (wall clock) in ``header.stamp``. A subscriber
prints ``READY`` once subscribed, then, from its first message on, counts for ``--duration``
seconds and prints ``RESULT {"count", "rate", "p50_us", "p99_us"}``. A publisher sends as fast as
it can (``--rate 0``) or at ``--rate`` Hz until stopped.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time
from typing import Any

__all__ = ["main"]

_WIDTH, _HEIGHT = 640, 480
_BATCH = 200  # a fast publisher yields to its loop every so many messages


def _report(latencies_ns: list[int], seconds: float) -> None:
    ordered = sorted(latencies_ns) or [0]
    result = {
        "count": len(latencies_ns),
        "rate": len(latencies_ns) / seconds if seconds > 0 else 0.0,
        "p50_us": statistics.median(ordered) / 1000,
        "p99_us": ordered[min(len(ordered) - 1, int(len(ordered) * 0.99))] / 1000,
    }
    print("RESULT " + json.dumps(result), flush=True)


class _Window:
    """Latencies of the messages that arrive in ``duration`` s from the first one."""

    def __init__(self, duration_s: float) -> None:
        self.duration_s = duration_s
        self.first_ns = 0
        self.latencies: list[int] = []
        self.done = False

    def add(self, sec: int, nanosec: int) -> None:
        now = time.time_ns()
        if not self.first_ns:
            self.first_ns = now
        if now - self.first_ns > self.duration_s * 1e9:
            self.done = True
            return
        self.latencies.append(now - (sec * 1_000_000_000 + nanosec))


# -- rclpy ------------------------------------------------------------------------------------------


def _rclpy(args: argparse.Namespace) -> None:
    import rclpy
    from rclpy.node import Node
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    from rclpy.subscription import RCLError

    if args.image:
        from sensor_msgs.msg import Image as Message
    else:
        from geometry_msgs.msg import PointStamped as Message
    rclpy.init()
    node = Node(f"bench_{args.mode.replace('-', '_')}")
    qos = QoSProfile(depth=1000 if not args.image else 5, reliability=ReliabilityPolicy.RELIABLE)
    if args.mode == "rclpy-sub":
        window = _Window(args.duration)
        node.create_subscription(Message, args.topic, lambda m: window.add(m.header.stamp.sec, m.header.stamp.nanosec), qos)
        print("READY", flush=True)
        while not window.done:
            rclpy.spin_once(node, timeout_sec=0.5)
        _report(window.latencies, args.duration)
        return
    publisher = node.create_publisher(Message, args.topic, qos)
    message = Message()
    if args.image:
        message.height, message.width, message.encoding, message.step = _HEIGHT, _WIDTH, "rgb8", _WIDTH * 3
        message.data = bytes(_WIDTH * _HEIGHT * 3)
    print("READY", flush=True)
    period = 1.0 / args.rate if args.rate else 0.0
    next_at = time.monotonic()
    while True:
        now = time.time_ns()
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(now, 1_000_000_000)
        try:
            publisher.publish(message)
        except RCLError:  # a reliable writer whose readers fell behind refuses for a while: go on
            time.sleep(0.001)
        if period:
            next_at += period
            time.sleep(max(0.0, next_at - time.monotonic()))


# -- Skydeck ----------------------------------------------------------------------------------------


def _skydeck(args: argparse.Namespace) -> None:
    from services.runtime import Node, spin
    from shared_models.builtin_interfaces import Time
    from shared_models.geometry_msgs import PointStamped
    from shared_models.sensor_msgs import Image

    message_type: Any = Image if args.image else PointStamped

    class Bench(Node):
        def __init__(self) -> None:
            super().__init__(f"bench_{args.mode.replace('-', '_')}")
            if args.mode == "skydeck-sub":
                self.window = _Window(args.duration)
                self.create_subscription(message_type, args.topic, self.received, 1000)
            else:
                self.publisher = self.create_publisher(message_type, args.topic, 1000)

        def received(self, message: Any) -> None:
            self.window.add(message.header.stamp.sec, message.header.stamp.nanosec)
            if self.window.done:
                _report(self.window.latencies, args.duration)
                self.destroy_node()

        async def start(self) -> None:
            await super().start()
            print("READY", flush=True)
            if args.mode == "skydeck-pub":
                self._spawn(self.publish_forever())

        async def publish_forever(self) -> None:
            template = message_type(height=_HEIGHT, width=_WIDTH, encoding="rgb8", step=_WIDTH * 3,
                                    data=bytes(_WIDTH * _HEIGHT * 3)) if args.image else message_type()
            period = 1.0 / args.rate if args.rate else 0.0
            loop = asyncio.get_running_loop()
            next_at = loop.time()
            sent = 0
            while True:
                message = template.model_copy(deep=False)
                message.header = template.header.model_copy(update={"stamp": Time.from_nsec(time.time_ns())})
                self.publisher.publish(message)
                sent += 1
                if period:
                    next_at += period
                    await asyncio.sleep(max(0.0, next_at - loop.time()))
                elif sent % _BATCH == 0:
                    await asyncio.sleep(0)

    spin(Bench())


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=("rclpy-pub", "rclpy-sub", "skydeck-pub", "skydeck-sub"))
    parser.add_argument("topic")
    parser.add_argument("--rate", type=float, default=0.0, help="Hz; 0: as fast as it can")
    parser.add_argument("--duration", type=float, default=3.0, help="a subscriber's window, seconds")
    parser.add_argument("--image", action="store_true", help="640x480 rgb8 images instead of small messages")
    args = parser.parse_args(argv)
    (_rclpy if args.mode.startswith("rclpy") else _skydeck)(args)


if __name__ == "__main__":
    main()
