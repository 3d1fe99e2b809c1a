"""The ball world's one option: ``--balls``."""

from __future__ import annotations

from pydantic import Field

from sim_server.settings import SimSettings


class BallSettings(SimSettings):
    balls: int = Field(default=1, ge=1, le=3, description="number of balls, 1-3 (default 1)")
