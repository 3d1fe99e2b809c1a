"""ROS names of topics, services and nodes.

A valid absolute name is ``/`` followed by one or more tokens ``[A-Za-z_][A-Za-z0-9_]*`` separated
by single ``/``: ``/drone/pose``. A token may start with ``_`` as in ROS 2, whose hidden names
(an action's ``/fibonacci/_action/send_goal``) do; never with a digit. Relative names (``perception/boxes``) are resolved against a
namespace. There is no ``~`` (private names) and no trailing ``/``. Names under the core's own
routes (:data:`RESERVED_PREFIXES`) are refused, since topics and services are URL paths too.

Every invalid name raises :class:`InvalidNameError` (a ``ValueError``) whose message quotes the
name and points at the bad part.
"""

from __future__ import annotations

from shared_models.close_codes import Close
from shared_models.errors import SkydeckError

__all__ = [
    "RESERVED_PREFIXES",
    "InvalidNameError",
    "check_not_reserved",
    "resolve_name",
    "resolve_node_name",
]

# URL paths the core serves itself; a topic or service there would be unreachable.
RESERVED_PREFIXES: tuple[str, ...] = (
    "/api",
    "/docs",
    "/redoc",
    "/openapi.json",
    "/static",
    "/health",
    "/rosbridge",  # the rosbridge endpoint on the core's own port
)

_ALLOWED = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_/")


class InvalidNameError(SkydeckError, ValueError):
    """Raised for a topic, service or node name that is not a valid ROS name; carries ``name``."""

    http_status = 404
    close_code = Close.POLICY

    def __init__(self, name: str, reason: str) -> None:
        super().__init__(f"invalid name {name!r}: {reason}")
        self.name = name
        self.reason = reason


def _check_tokens(name: str, start: int) -> None:
    """Check the ``/``-separated tokens of ``name`` from index ``start`` on."""
    for index, char in enumerate(name):
        if char == "~":
            raise InvalidNameError(
                name,
                f"'~' at position {index} is not allowed (no private names: write the full name)",
            )
        if char not in _ALLOWED:
            raise InvalidNameError(
                name, f"{char!r} at position {index} is not allowed (letters, digits, _ and / only)"
            )
    if name.endswith("/") and len(name) > start:
        raise InvalidNameError(name, f"trailing '/' at position {len(name) - 1}")
    position = start
    for token in name[start:].split("/"):
        if not token:
            raise InvalidNameError(name, f"empty token at position {position}")
        if not (token[0].isalpha() or token[0] == "_"):
            raise InvalidNameError(
                name, f"token {token!r} at position {position} must start with a letter or '_'"
            )
        position += len(token) + 1


def check_not_reserved(name: str) -> str:
    """Return the absolute ``name`` unchanged, or raise if it lies under a core route (``/api/x``)."""
    for prefix in RESERVED_PREFIXES:
        if name == prefix or name.startswith(prefix + "/"):
            raise InvalidNameError(
                name, f"{prefix} is reserved for the core's own routes; choose another name"
            )
    return name


def resolve_name(name: str, namespace: str = "/") -> str:
    """The absolute form of a topic or service name, checked.

    Example::

        resolve_name("my_point")                  # "/my_point"
        resolve_name("boxes", namespace="/perception")  # "/perception/boxes"
        resolve_name("/drone/pose")               # "/drone/pose"
    """
    if not name:
        raise InvalidNameError(name, "a name needs at least one token, e.g. /my_topic")
    if name.startswith("/"):
        if name == "/":
            raise InvalidNameError(
                name, "a name needs at least one token after '/', e.g. /my_topic"
            )
        _check_tokens(name, 1)
        return check_not_reserved(name)
    _check_tokens(name, 0)
    namespace = namespace.rstrip("/") if namespace != "/" else namespace
    if namespace != "/":
        if not namespace.startswith("/"):
            raise InvalidNameError(namespace, "a namespace must be absolute (start with '/')")
        _check_tokens(namespace, 1)
    return check_not_reserved(namespace.rstrip("/") + "/" + name)


def resolve_node_name(name: str) -> str:
    """The absolute form of a node name, a single token: ``"talker"`` -> ``"/talker"``."""
    start = 1 if name.startswith("/") else 0
    if len(name) == start:
        raise InvalidNameError(name, "a node name needs one token, e.g. talker")
    _check_tokens(name, start)
    if "/" in name[start:]:
        position = name.index("/", start)
        raise InvalidNameError(
            name, f"'/' at position {position}: a node name is a single token, with no namespace"
        )
    return "/" + name[start:]
