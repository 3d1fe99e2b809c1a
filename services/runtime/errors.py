"""Exceptions of the node SDK (the whole project's tree is drawn in :mod:`shared_models.errors`).

    SkydeckError                  base of everything Skydeck raises on purpose
    ├── NodeError                 misuse of a node (entity on a destroyed node, two types on one topic)
    └── ServiceError              a service call that got no answer (rospy's ServiceException)
        ├── ServiceUnavailableError   nobody hosts the service, or its node cannot be reached
        ├── ServiceTimeoutError       the node did not answer in time
        └── ServiceCallRejectedError  the node refused the request (HTTP 4xx, e.g. a bad body)

A service that answers ``success: false`` did answer: that is a response, not an exception.
"""

from __future__ import annotations

from shared_models.errors import SkydeckError

__all__ = [
    "NodeError",
    "ServiceCallRejectedError",
    "ServiceError",
    "ServiceException",
    "ServiceTimeoutError",
    "ServiceUnavailableError",
    "SkydeckError",
]


class NodeError(SkydeckError):
    """A node was used in a way it cannot honour (raised at the call that did it)."""


class ServiceError(SkydeckError):
    """A service call got no answer; ``name`` is the service."""

    http_status = 502

    def __init__(self, name: str, message: str) -> None:
        super().__init__(message)
        self.name = name


class ServiceUnavailableError(ServiceError):
    """No node hosts the service, or the hosting node cannot be reached."""

    http_status = 503


class ServiceTimeoutError(ServiceError):
    """The hosting node did not answer within the call's timeout."""

    http_status = 504


class ServiceCallRejectedError(ServiceError):
    """The hosting node refused the request (for example, a body that does not fit the type)."""

    def __init__(self, name: str, message: str, status_code: int) -> None:
        super().__init__(name, message)
        self.status_code = status_code


# rospy's name, so `except rospy.ServiceException` ports as `except ServiceException`.
ServiceException = ServiceError

# Invalid names raise shared_models.InvalidNameError (a ValueError), shared with the core and CLI.
