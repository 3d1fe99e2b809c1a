"""Running the core under uvicorn (``skydeck core``); Ctrl-C and SIGTERM stop it with exit 0."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import signal
from collections.abc import Iterator

import uvicorn

from services.core.app import create_app
from services.core.settings import CoreSettings
from services.runtime.executor import configure_logging, run

__all__ = ["serve"]


class _Server(uvicorn.Server):
    """uvicorn without re-raising the stop signal after shutdown (a supervisor reads that as a crash)."""

    @contextlib.contextmanager
    def capture_signals(self) -> Iterator[None]:
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, self._stop)
        try:
            yield
        finally:
            for sig in (signal.SIGINT, signal.SIGTERM):
                loop.remove_signal_handler(sig)

    def _stop(self) -> None:
        if self.should_exit:
            self.force_exit = True  # a second Ctrl-C does not wait for open connections
        self.should_exit = True


def serve(settings: CoreSettings | None = None) -> None:
    """Serve the core until Ctrl-C or SIGTERM."""
    settings = settings or CoreSettings()
    configure_logging(settings.log_level)
    logging.getLogger("skydeck.core").info(
        "core at http://%s:%d (dashboard /, every command /docs)", settings.host, settings.port
    )
    config = uvicorn.Config(
        create_app(settings),
        host=settings.host,
        port=settings.port,
        log_level="warning",
        access_log=False,
        ws_max_size=settings.max_message_bytes,
        ws_ping_interval=settings.ping_interval_s,
        ws_ping_timeout=settings.ping_timeout_s,
        ws_per_message_deflate=False,
    )
    run(_Server(config).serve())
