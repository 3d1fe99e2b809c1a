"""Typed ROS messages and service types for Skydeck (pydantic v2), and ROS-style names.

Messages live in one module per ROS package (``shared_models.geometry_msgs.PointStamped``...);
:func:`get_interface` imports all of them on first use (:mod:`shared_models.catalogue`), and the
exports load lazily, so importing :mod:`shared_models.errors` or ``names`` costs no message type.

Exceptions (descending from :class:`~shared_models.errors.SkydeckError`, and from the built-in
class a caller would expect)::

    ValueError
     └── InvalidNameError       a topic, service or node name that is not a valid ROS name
    LookupError
     └── UnknownInterfaceError  a type name no registered message or service has
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from shared_models.lazy import lazy_exports

if TYPE_CHECKING:
    from shared_models._message import ActionType, Message, ServiceType
    from shared_models.interfaces import (
        UnknownInterfaceError,
        all_interfaces,
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
    "ActionType",
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

_HOMES = {
    "ActionType": "shared_models._message",
    "RESERVED_PREFIXES": "shared_models.names",
    "InvalidNameError": "shared_models.names",
    "Message": "shared_models._message",
    "ServiceType": "shared_models._message",
    "UnknownInterfaceError": "shared_models.interfaces",
    "all_interfaces": "shared_models.interfaces",
    "get_interface": "shared_models.interfaces",
    "interface_names": "shared_models.interfaces",
    "interface_text": "shared_models.interfaces",
    "resolve_name": "shared_models.names",
    "resolve_node_name": "shared_models.names",
}

__getattr__ = lazy_exports(__name__, _HOMES)
