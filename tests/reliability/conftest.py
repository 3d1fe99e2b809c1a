"""The e2e ``launch`` fixture (a real `skydeck launch` on free ports), shared with tests/e2e."""

from __future__ import annotations

from tests.e2e.conftest import LaunchedSystem, launch

__all__ = ["LaunchedSystem", "launch"]
