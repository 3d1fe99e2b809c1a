"""Free TCP ports on loopback: is one free, and a run of free ones to start servers on.

The launch supervisor checks its ports before it starts anything; the benchmark and the tests
pick ports for the servers they start.
"""

from __future__ import annotations

import random
import socket

__all__ = ["free_port_block", "port_is_free"]

# Ports are picked below the range the kernel hands out to outgoing connections
# (/proc/sys/net/ipv4/ip_local_port_range, 32768-60999 by default): a port picked there can be
# taken by some client's connection between the pick and the server's bind.
_PICK_FROM = range(20000, 32000)


def port_is_free(port: int, host: str = "127.0.0.1") -> bool:
    """Whether a server could listen on ``port`` now (as servers do, with SO_REUSEADDR)."""
    with socket.socket() as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            probe.bind((host, port))
        except OSError:
            return False
    return True


def free_port_block(count: int = 1) -> int:
    """A base port such that base .. base+count-1 are all free on loopback right now."""
    for _ in range(500):
        base = random.randrange(_PICK_FROM.start, _PICK_FROM.stop - count)
        if all(port_is_free(base + offset) for offset in range(count)):
            return base
    raise RuntimeError(f"no {count} consecutive free loopback ports found")
