"""``rclpy.qos``: QoS profiles and policies.

The depth of a keep-last history is honoured (it is the queue size of the publisher's readers
and of the subscription); TRANSIENT_LOCAL durability makes a publisher latch its last message
for late subscribers. Reliability, deadline, lifespan and liveliness are accepted and have no
effect: Skydeck's links are TCP (always reliable), and a slow reader loses its oldest messages.
"""

from __future__ import annotations

from enum import Enum, IntEnum
from typing import Any

from services.ros.errors import RosFacadeError
from services.ros.rclpy.duration import Duration

__all__ = [
    "DurabilityPolicy",
    "HistoryPolicy",
    "InvalidQoSProfileException",
    "LivelinessPolicy",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSLivelinessPolicy",
    "QoSPresetProfiles",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ReliabilityPolicy",
    "qos_profile_action_status_default",
    "qos_profile_parameter_events",
    "qos_profile_parameters",
    "qos_profile_sensor_data",
    "qos_profile_services_default",
    "qos_profile_system_default",
]

_KEEP_ALL_DEPTH = 10_000  # "keep all" still needs a bound in memory
_DEFAULT_DEPTH = 10


class InvalidQoSProfileException(RosFacadeError, ValueError):
    """A QoS profile rclpy would refuse (no history and no depth, a negative depth)."""


class HistoryPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class ReliabilityPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class LivelinessPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


# The older names rclpy still accepts.
QoSHistoryPolicy = HistoryPolicy
QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSLivelinessPolicy = LivelinessPolicy


class QoSProfile:
    """``QoSProfile(depth=10)``, ``QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1,
    durability=DurabilityPolicy.TRANSIENT_LOCAL)``; history or depth is required, as in rclpy."""

    def __init__(
        self,
        *,
        history: HistoryPolicy | int | None = None,
        depth: int | None = None,
        reliability: ReliabilityPolicy | int = ReliabilityPolicy.RELIABLE,
        durability: DurabilityPolicy | int = DurabilityPolicy.VOLATILE,
        lifespan: Duration | None = None,
        deadline: Duration | None = None,
        liveliness: LivelinessPolicy | int = LivelinessPolicy.SYSTEM_DEFAULT,
        liveliness_lease_duration: Duration | None = None,
        avoid_ros_namespace_conventions: bool = False,
    ) -> None:
        if history is None and depth is None:
            raise InvalidQoSProfileException("History and/or depth settings are required to create a QoSProfile")
        if depth is not None and (not isinstance(depth, int) or isinstance(depth, bool) or depth < 0):
            raise InvalidQoSProfileException(f"depth must be a non-negative integer, got {depth!r}")
        self.history = HistoryPolicy(history if history is not None else HistoryPolicy.KEEP_LAST)
        self.depth = depth if depth is not None else 0
        self.reliability = ReliabilityPolicy(reliability)
        self.durability = DurabilityPolicy(durability)
        self.lifespan = lifespan or Duration()
        self.deadline = deadline or Duration()
        self.liveliness = LivelinessPolicy(liveliness)
        self.liveliness_lease_duration = liveliness_lease_duration or Duration()
        self.avoid_ros_namespace_conventions = avoid_ros_namespace_conventions

    @property
    def queue_depth(self) -> int:
        """The queue size Skydeck uses for this profile."""
        if self.history == HistoryPolicy.KEEP_ALL:
            return _KEEP_ALL_DEPTH
        return self.depth or _DEFAULT_DEPTH

    @property
    def latched(self) -> bool:
        return self.durability == DurabilityPolicy.TRANSIENT_LOCAL

    def __eq__(self, other: object) -> bool:
        return isinstance(other, QoSProfile) and vars(self) == vars(other)

    def __repr__(self) -> str:
        return (
            f"QoSProfile(history={self.history.name}, depth={self.depth}, reliability="
            f"{self.reliability.name}, durability={self.durability.name})"
        )


def qos_profile(qos: Any) -> QoSProfile:
    """A ``qos_profile`` argument as rclpy takes it: a QoSProfile, or an int for the depth."""
    if isinstance(qos, QoSProfile):
        return qos
    if isinstance(qos, int) and not isinstance(qos, bool):
        return QoSProfile(depth=qos)
    if isinstance(qos, QoSPresetProfiles):
        return qos.value
    raise TypeError(f"qos_profile must be a QoSProfile or an int (the history depth), got {qos!r}")


qos_profile_system_default = QoSProfile(history=HistoryPolicy.SYSTEM_DEFAULT, depth=0)
qos_profile_sensor_data = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=5, reliability=ReliabilityPolicy.BEST_EFFORT
)
qos_profile_services_default = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10)
qos_profile_parameters = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1000)
qos_profile_parameter_events = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1000)
qos_profile_action_status_default = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL
)


class QoSPresetProfiles(Enum):
    """The named profiles: ``QoSPresetProfiles.SENSOR_DATA.value``."""

    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        return cls[name.upper()].value
