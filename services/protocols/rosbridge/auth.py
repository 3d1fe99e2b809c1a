"""rosbridge's ``auth`` op: ROS 1's rosauth, with the core's write token as its secret.

A client unlocks writing (publish, call, host) on a connection opened without the token by
sending either the token itself as ``mac`` (what a script that has the token does), or what
rosauth's ``ros_mac_authentication`` checks: ``mac`` the hex SHA-512 of ``secret + client + dest
+ rand + t + level + end`` (``t`` and ``end`` as whole seconds), where a trusted server that
holds the token made it for the client, ``t`` within 5 s of now and ``end`` still ahead. So a
web page can be given a MAC that expires instead of the token (roslibjs's ``ros.authenticate``).
"""

from __future__ import annotations

import hashlib
import hmac
import time

from services.protocols.rosbridge.ops import Auth
from services.runtime.auth import token_is_valid

__all__ = ["ALLOWED_TIME_DELTA_S", "authenticates", "rosauth_mac"]

ALLOWED_TIME_DELTA_S = 5.0  # rosauth's default allowed_time_delta


def authenticates(op: Auth, token: str | None) -> bool:
    """Whether ``op`` proves the client holds ``token`` (the token itself, or rosauth's MAC)."""
    if not token:
        return True  # no token set: everyone may write already
    if token_is_valid(token, op.mac):
        return True
    now = time.time()
    t, end = _seconds(op.t), _seconds(op.end)
    if abs(now - t) >= ALLOWED_TIME_DELTA_S or end <= now:
        return False
    expected = rosauth_mac(token, op.client, op.dest, op.rand, int(t), op.level, int(end))
    return hmac.compare_digest(expected, op.mac.lower())


def rosauth_mac(secret: str, client: str, dest: str, rand: str, t: int, level: str, end: int) -> str:
    """rosauth's MAC: the hex SHA-512 of the fields in its order, times in whole seconds."""
    return hashlib.sha512(f"{secret}{client}{dest}{rand}{t}{level}{end}".encode()).hexdigest()


def _seconds(value: float | dict[str, int]) -> float:
    """A time as rosbridge clients send it: seconds, or ROS 1's ``{"secs", "nsecs"}``."""
    if isinstance(value, dict):
        return value.get("secs", value.get("sec", 0)) + value.get("nsecs", value.get("nanosec", 0)) / 1e9
    return float(value)
