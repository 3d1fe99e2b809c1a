"""Running the core under uvicorn (``skydeck core``)."""

from __future__ import annotations

import logging

import uvicorn

from services.core.app import create_app
from services.core.settings import CoreSettings

__all__ = ["serve"]


def serve(settings: CoreSettings | None = None) -> None:
    """Serve the core until Ctrl-C or SIGTERM."""
    settings = settings or CoreSettings()
    logging.basicConfig(level=settings.log_level.upper(), format="[%(levelname)s] [%(name)s] %(message)s")
    logging.getLogger("skydeck.core").info(
        "core at http://%s:%d (dashboard /, every command /docs)", settings.host, settings.port
    )
    uvicorn.run(
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
