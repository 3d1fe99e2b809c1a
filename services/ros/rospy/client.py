"""``rospy.init_node``, ``rospy.spin``, ``rospy.myargv``, ``rospy.wait_for_message``.

    rospy.init_node("perception")
    rospy.Subscriber("/simulator/boxes", PoseArray, callback)
    rospy.spin()

``init_node`` makes the process's node: an SDK node (:class:`services.runtime.Node`) that serves
its topics and services, registers with the core (``SKYDECK_CORE_URL``, what ROS 1 calls the
master) and logs to ``/rosout``. It reads ROS 1's command-line arguments (``name:=value``
remaps, ``__name:=``, ``__ns:=``, ``_param:=value`` private parameters, which it sets on the
parameter server as rospy does), follows the simulator's ``/clock`` when the ``/use_sim_time``
parameter is true (or ``skydeck run --use-sim-time``), and, unless ``disable_signals=True``,
makes SIGINT and SIGTERM shut the node down. As rospy's does, it waits for the core to answer.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from typing import Any

from services.ros.bridge import bridge
from services.ros.pacing import thread_waits_for_work, wait_for_first_clock
from services.ros.rclpy.logging import node_logger
from services.ros.rospy.core import process
from services.ros.rospy.exceptions import CoreUnreachableException, ROSException
from services.ros.rospy.log import logwarn, severity
from services.ros.rospy.params import get_param, set_param
from services.runtime.ros_args import ROS_ARGS, RosArguments, parse_ros1_args, split_ros_args
from services.runtime.settings import NodeSettings, node_settings
from shared_models import Message

__all__ = ["init_node", "myargv", "spin", "wait_for_message"]

_CORE_RETRY_S = 1.0
_SPIN_WAKE_S = 1.0  # spin's wait on shutdown, bounded so Python can deliver signals meanwhile


def init_node(
    name: str, argv: list[str] | None = None, anonymous: bool = False, log_level: int | None = None,
    disable_rostime: bool = False, disable_rosout: bool = False, disable_signals: bool = False,
    xmlrpc_port: int = 0, tcpros_port: int = 0,
) -> None:  # fmt: skip
    """Make this process's node ``name`` (see the module docstring); once per process."""
    from services.runtime.executor import configure_logging
    from services.runtime.node import Node as RuntimeNode
    from services.runtime.parameter import Parameter

    given = (name, argv, anonymous, log_level, disable_rostime, disable_rosout, disable_signals)
    if process.node is not None:
        if process.init_arguments == given:
            return
        raise ROSException(
            f"rospy.init_node() has already been called with different arguments: {process.init_arguments}"
        )
    if not isinstance(name, str) or not name:
        raise ValueError(f"init_node needs a node name, got {name!r}")
    if "/" in name.lstrip("/"):
        raise ValueError("namespaces are not allowed in node names: use __ns:=/robot1 or ROS_NAMESPACE")
    name = name.lstrip("/")
    configure_logging()
    if anonymous:
        name = f"{name}_{os.getpid()}_{time.time_ns() // 1_000_000 % 1_000_000_000}"
    words = list(sys.argv[1:] if argv is None else argv)
    ros1 = parse_ros1_args(split_ros_args(words)[0] if ROS_ARGS in words else words)[1]
    settings = node_settings()
    use_sim_time = _use_sim_time(settings)
    node = RuntimeNode(
        name,
        namespace=settings.ros_namespace or None,
        settings=settings,
        use_global_arguments=argv is None,  # `skydeck run` put the command line's there
        cli_args=_as_ros2_args(ros1) if argv is not None else None,
        parameter_overrides=[Parameter("use_sim_time", value=True)] if use_sim_time else None,
    )
    logger = node_logger(node, rosout=not disable_rosout)
    if log_level is not None:
        logger.set_level(severity(log_level))
    process.logger = logger
    process.node = node
    process.init_arguments = given
    for rule in ros1.parameter_rules:  # `_rate:=10`: rospy sets them as the node's private ones
        for key, value in rule.values.items():
            set_param(f"~{key}", value)
    bridge.start_node(node)
    if use_sim_time:
        wait_for_first_clock(node.get_clock())
    if not disable_signals:
        _shut_down_on_signals()


def _use_sim_time(settings: NodeSettings) -> bool:
    """``skydeck run --use-sim-time``, or the ``/use_sim_time`` parameter (waiting for the core,
    as rospy's init_node waits for the master)."""
    if settings.use_sim_time:
        return True
    warned = False
    while True:
        try:
            return bool(get_param("/use_sim_time", False))
        except CoreUnreachableException as error:
            if not warned:
                logwarn("%s; will keep trying", error)
                warned = True
            time.sleep(_CORE_RETRY_S)


def _as_ros2_args(arguments: RosArguments) -> list[str]:
    """ROS 1 remaps (``from:=to``, ``__name:=``, ``__ns:=``) as the SDK's ``-r`` rules."""
    words: list[str] = []
    for rule in arguments.remap_rules:
        source = "__node" if rule.source == "__name" else rule.source
        words += ["-r", f"{source}:={rule.target}"]
    return words


def _shut_down_on_signals() -> None:
    """SIGINT and SIGTERM shut the node down, then go on to the handler that was there (for
    SIGINT, Python's KeyboardInterrupt), as rospy's handlers do."""
    if threading.current_thread() is not threading.main_thread():
        return
    for signum in (signal.SIGINT, signal.SIGTERM):
        previous = signal.getsignal(signum)

        def handler(number: int, frame: Any, previous: Any = previous) -> None:
            process.shutdown(f"signal-{signal.Signals(number).name}", stop_here=False)
            if callable(previous):
                previous(number, frame)

        signal.signal(signum, handler)


def spin() -> None:
    """Block until the node shuts down (Ctrl-C, ``signal_shutdown``); callbacks run meanwhile
    on their own threads."""
    process.require_node("rospy.spin")
    thread_waits_for_work()
    try:
        while not process.wait(_SPIN_WAKE_S):
            pass
    except KeyboardInterrupt:
        process.shutdown("keyboard interrupt")


def myargv(argv: list[str] | None = None) -> list[str]:
    """``argv`` (default ``sys.argv``) without ROS's arguments (``name:=value``, ``--ros-args ...``)."""
    args = list(sys.argv if argv is None else argv)
    if ROS_ARGS in args:
        args = split_ros_args(args)[0]
    return [arg for arg in args if ":=" not in arg]


def wait_for_message(topic: str, topic_type: type[Message], timeout: float | None = None) -> Any:
    """The next message on ``topic``; ROSException if none comes within ``timeout`` seconds."""
    from services.ros.rospy.topics import Subscriber

    got: list[Any] = []
    arrived = threading.Event()

    def take(msg: Any) -> None:
        if not got:
            got.append(msg)
            arrived.set()

    subscriber = Subscriber(topic, topic_type, take)
    try:
        if not _wait(arrived, timeout):
            raise ROSException(f"timeout exceeded while waiting for message on topic {subscriber.resolved_name}")
    finally:
        subscriber.unregister()
    return got[0]


def _wait(event: threading.Event, timeout: float | None) -> bool:
    deadline = None if timeout is None else time.monotonic() + timeout
    while not event.is_set():
        if process.is_shutdown():
            from services.ros.rospy.exceptions import ROSInterruptException

            raise ROSInterruptException("ROS shutdown request")
        left = _SPIN_WAKE_S if deadline is None else min(_SPIN_WAKE_S, deadline - time.monotonic())
        if left <= 0:
            return False
        event.wait(left)
    return True
