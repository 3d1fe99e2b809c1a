"""``rospy.exceptions``: what rospy raises, with rospy's names and hierarchy, under Skydeck's
one root (``SkydeckError``, an Exception as rospy's are).

    SkydeckError
    ├── ROSException                      rospy's base
    │   ├── ROSInitException              rospy used before ``init_node``, or init_node called twice
    │   ├── ROSInterruptException         a sleep cut short by shutdown (also a KeyboardInterrupt)
    │   │   └── ROSTimeMovedBackwardsException
    │   ├── ServiceException              a service call that failed (no server, or it raised)
    │   ├── ROSSerializationException     a message that does not fit its type
    │   ├── TransportException
    │   └── CoreUnreachableException      the core (ROS 1's master) does not answer
    └── ROSInternalException

Uncaught, ``skydeck run`` prints any of them as one line (``skydeck: error: ...``), such as
``CoreUnreachableException``'s, which says to start the core, as rospy says the master is not
running; ``ROSInterruptException`` ends the program quietly, as Ctrl-C does.
"""

from __future__ import annotations

from shared_models.errors import SkydeckError

__all__ = [  # rospy's own names (what `from rospy import *` has of this module)
    "ROSException",
    "ROSInitException",
    "ROSInternalException",
    "ROSInterruptException",
    "ROSSerializationException",
    "ROSTimeMovedBackwardsException",
    "ServiceException",
    "TransportException",
]


class ROSException(SkydeckError):
    """Base of rospy's exceptions."""


class ROSInitException(ROSException):
    """rospy was used in a way that needs ``init_node`` first (or init_node was called twice)."""


class ROSInterruptException(ROSException, KeyboardInterrupt):
    """A sleep (``Rate.sleep``, ``rospy.sleep``) ended because the node shut down."""


class ROSTimeMovedBackwardsException(ROSInterruptException):
    """ROS time went back during a sleep (a simulator reset); ``time`` is how far."""

    def __init__(self, time: float) -> None:
        super().__init__("ROS time moved backwards")
        self.time = time


class ServiceException(ROSException):
    """A service call failed: nobody serves it, it could not be reached, or its handler raised."""


class ROSSerializationException(ROSException):
    """A message could not be sent as its type."""


class TransportException(ROSException):
    """A connection failed."""


class CoreUnreachableException(ROSException):
    """The core (what ROS 1 calls the master) did not answer."""


class ROSInternalException(SkydeckError):
    """Something went wrong inside rospy itself."""
