"""What tf2 raises, with tf2's names, hierarchy and messages, under Skydeck's one root.

    SkydeckError
    └── TransformException             tf2's base (ROS 1's ``tf.Exception``)
        ├── LookupException            a frame the buffer has never heard of
        ├── ConnectivityException      both frames known, but in two unconnected trees
        ├── ExtrapolationException     the time asked is outside the data the buffer holds
        ├── InvalidArgumentException   an empty frame name, one starting with '/', a bad time
        └── TimeoutException           exported for ``except`` clauses; a lookup whose timeout
                                       passes raises what it would have raised at once, as
                                       tf2_ros's Python Buffer does

Uncaught, ``skydeck run`` prints any of them as one line (``skydeck: error: ...``).
"""

from __future__ import annotations

from shared_models.errors import SkydeckError

__all__ = [
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
]


class TransformException(SkydeckError):
    """Base of tf2's exceptions: a transform could not be had."""


class LookupException(TransformException):
    """A frame the buffer has never heard of (``"base_link" passed to lookupTransform argument
    source_frame does not exist.``): is its broadcaster running, and is the name right?"""


class ConnectivityException(TransformException):
    """The two frames are in trees with no link between them."""


class ExtrapolationException(TransformException):
    """The time asked for is newer than the newest data, or older than the oldest kept."""


class InvalidArgumentException(TransformException):
    """An argument tf2 cannot take: an empty frame name, one starting with '/', a bad time."""


class TimeoutException(TransformException):
    """A wait for a transform ran out of time."""
