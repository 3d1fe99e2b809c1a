"""Running nodes (rclpy's executor): ``spin(node)``, with Ctrl-C and SIGTERM stopping it cleanly."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import signal
from collections.abc import Coroutine
from typing import Any, TypeVar

from services.runtime.errors import SkydeckError
from services.runtime.logger import RosLogFormatter
from services.runtime.node import Node

__all__ = ["init", "run", "shutdown", "spin"]

T = TypeVar("T")


def init(args: list[str] | None = None) -> None:
    """Nothing to set up (kept so ``rclpy.init()`` ports as is); logging goes to stderr."""
    configure_logging()


def shutdown() -> None:
    """Nothing to tear down (kept so ``rclpy.shutdown()`` ports as is)."""


def configure_logging(level: str = "INFO") -> None:
    """One line per record on stderr, unless the program configured logging itself."""
    root = logging.getLogger()
    if not root.handlers:
        handler = logging.StreamHandler()
        handler.setFormatter(RosLogFormatter())
        logging.basicConfig(level=level.upper(), handlers=[handler])


def run(main: Coroutine[Any, Any, T]) -> T:
    """``asyncio.run(main)`` on uvloop: every Skydeck process runs its loop here.

    uvloop's sockets and timers cost about half of asyncio's per message (docs/performance.md);
    where it is missing, the standard loop runs the same code.
    """
    try:
        import uvloop
    except ImportError:
        return asyncio.run(main)
    with asyncio.Runner(loop_factory=uvloop.new_event_loop) as runner:
        return runner.run(main)


def spin(node: Node) -> None:
    """Run ``node`` until Ctrl-C, SIGTERM or ``node.destroy_node()``; returns when it has stopped.

    A node that cannot start (its port taken, say) logs one line and exits with status 1.
    """
    configure_logging(node.settings.log_level)
    try:
        run(_spin(node))
    except KeyboardInterrupt:
        pass
    except SkydeckError as error:
        logging.getLogger("skydeck.runtime").error("%s: %s", node.get_name(), error)
        raise SystemExit(1) from None


async def _spin(node: Node) -> None:
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        with contextlib.suppress(NotImplementedError, RuntimeError):
            loop.add_signal_handler(sig, node.destroy_node)
    await node.run_until_stopped()
