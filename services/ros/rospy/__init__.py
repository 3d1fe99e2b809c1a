"""Skydeck's rospy (ROS 1's Python client library): ``import rospy`` in a file ``skydeck run`` runs.

    import rospy
    from geometry_msgs.msg import PoseArray

    def callback(message):
        rospy.loginfo("Got %d boxes", len(message.poses))

    rospy.init_node("perception")
    rospy.Subscriber("/simulator/boxes", PoseArray, callback)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        rate.sleep()

A thin façade over the SDK (:mod:`services.runtime`): the process's node is an SDK node on the
bridge's event loop (:mod:`services.ros.bridge`); subscriber callbacks, service handlers and
timers run on threads of their own, as rospy's do. What it has and where it differs from rospy
is in docs/ros.md.
"""

from __future__ import annotations

from services.ros.errors import not_provided_attributes
from services.ros.rospy import exceptions, log
from services.ros.rospy.client import (
    init_node,
    myargv,
    spin,
    wait_for_message,
)
from services.ros.rospy.core import (
    get_caller_id,
    get_name,
    get_namespace,
    is_initialized,
    is_shutdown,
    is_shutdown_requested,
    on_shutdown,
    resolve_name,
    signal_shutdown,
)
from services.ros.rospy.exceptions import *  # noqa: F403 (its __all__, listed once there)
from services.ros.rospy.graph import get_published_topics
from services.ros.rospy.log import *  # noqa: F403 (its __all__, listed once there)
from services.ros.rospy.params import (
    delete_param,
    get_param,
    get_param_cached,
    get_param_names,
    has_param,
    search_param,
    set_param,
)
from services.ros.rospy.rostime import Duration, Time, get_rostime, get_time
from services.ros.rospy.services import Service, ServiceProxy, wait_for_service
from services.ros.rospy.timer import Rate, Timer, TimerEvent, sleep
from services.ros.rospy.topics import Publisher, Subscriber
from shared_models.std_msgs import Header

__all__ = [
    "Duration",
    "Header",
    "Publisher",
    "Rate",
    "Service",
    "ServiceProxy",
    "Subscriber",
    "Time",
    "Timer",
    "TimerEvent",
    "delete_param",
    "get_caller_id",
    "get_name",
    "get_namespace",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "get_published_topics",
    "get_rostime",
    "get_time",
    "has_param",
    "init_node",
    "is_initialized",
    "is_shutdown",
    "is_shutdown_requested",
    "myargv",
    "on_shutdown",
    "resolve_name",
    "search_param",
    "set_param",
    "signal_shutdown",
    "sleep",
    "spin",
    "wait_for_message",
    "wait_for_service",
]
__all__ += exceptions.__all__
__all__ += log.__all__

# rospy names a course may meet that Skydeck does not have: one line each, not an AttributeError.
_NOT_PROVIDED = frozenset(
    {
        "AnyMsg",
        "SubscribeListener",
        "get_master",
        "get_node_uri",
        "get_ros_root",
        "get_param_server_cache",
        "set_param_raw",
        "names",
        "impl",
        "msproxy",
        "numpy_msg",
    }
)


__getattr__ = not_provided_attributes("rospy", _NOT_PROVIDED)
