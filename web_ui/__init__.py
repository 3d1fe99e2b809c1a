"""The browser dashboard, served by the core at ``/`` with its assets under ``/static/...``.

Plain HTML, CSS and ES modules: no build step, no JavaScript library, nothing fetched from
outside the machine. ``STATIC_DIR`` holds ``index.html`` and the assets.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["STATIC_DIR"]

STATIC_DIR: Path = Path(__file__).resolve().parent / "static"
