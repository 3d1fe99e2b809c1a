"""Typed ROS messages and service types for Skydeck (pydantic v2), and ROS-style names.

Messages live in one module per ROS package (``shared_models.geometry_msgs.PointStamped``...);
importing this package imports all of them, so :func:`get_interface` knows every type.

Exceptions (both plain built-in subclasses, so callers need no Skydeck base class)::

    ValueError
     └── InvalidNameError       a topic, service or node name that is not a valid ROS name
    LookupError
     └── UnknownInterfaceError  a type name no registered message or service has
"""

# Imported for their registration side effect: every message module, dependencies first.
from shared_models import (  # noqa: F401
    builtin_interfaces,
    geometry_msgs,
    mavros_msgs,
    nav_msgs,
    neato2_interfaces,
    rcl_interfaces,
    ros_workshop,
    rosgraph_msgs,
    sensor_msgs,
    std_msgs,
    std_srvs,
    tf2_msgs,
    visualization_msgs,
)
from shared_models._message import Message, ServiceType, all_interfaces
from shared_models.interfaces import (
    UnknownInterfaceError,
    get_interface,
    interface_names,
    interface_text,
)
from shared_models.names import (
    RESERVED_PREFIXES,
    InvalidNameError,
    resolve_name,
    resolve_node_name,
)

__all__ = [
    "RESERVED_PREFIXES",
    "InvalidNameError",
    "Message",
    "ServiceType",
    "UnknownInterfaceError",
    "all_interfaces",
    "get_interface",
    "interface_names",
    "interface_text",
    "resolve_name",
    "resolve_node_name",
]
