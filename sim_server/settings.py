"""The simulator's options: flags ``--world/--seed/--speed/--boxes/--robots/--obstacles`` and
``--camera-width/--camera-height/--camera-rate``, or ``SKYDECK_SIM_*`` variables. Pure settings: importing this loads no PyBullet."""

from __future__ import annotations

import math
import random
from typing import Literal

from pydantic import Field, ValidationInfo, field_validator
from pydantic_core import PydanticCustomError
from pydantic_settings import BaseSettings, SettingsConfigDict

from sim_server.limits import DEFAULT_BOXES, MAX_BOXES
from sim_server.robot.limits import DEFAULT_OBSTACLES, MAX_OBSTACLES, MAX_ROBOTS

__all__ = [
    "MAX_CAMERA_HEIGHT",
    "MAX_CAMERA_RATE_HZ",
    "MAX_CAMERA_WIDTH",
    "MIN_CAMERA_RATE_HZ",
    "MIN_CAMERA_SIDE",
    "SimSettings",
    "draw_seed",
]

MIN_CAMERA_SIDE = 16
MAX_CAMERA_WIDTH = 640
MAX_CAMERA_HEIGHT = 480
MIN_CAMERA_RATE_HZ = 0.1
MAX_CAMERA_RATE_HZ = 30.0


def draw_seed() -> int:
    """A random 32-bit world seed (a world built without one draws one)."""
    return random.SystemRandom().getrandbits(32)


class SimSettings(BaseSettings):
    """Which world, and its options; each world's own options are refused for the other."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_SIM_", extra="ignore")

    world: Literal["drone", "robot", "soccer"] = "drone"  # soccer: the robot world with a ball
    seed: int | None = Field(default=None, ge=0, le=2**32 - 1, description="None draws one")
    speed: float | None = Field(
        default=1.0, description="times real time; None is as fast as possible"
    )
    boxes: int = Field(
        default=DEFAULT_BOXES, ge=0, le=MAX_BOXES, description="the drone world's falling boxes"
    )
    robots: int | None = Field(
        default=None, ge=1, le=MAX_ROBOTS, description="the robot world's robots (default 1)"
    )
    obstacles: int | None = Field(
        default=None,
        ge=0,
        le=MAX_OBSTACLES,
        description=f"the robot world's box obstacles (default {DEFAULT_OBSTACLES})",
    )

    camera_width: int = Field(
        default=320, ge=MIN_CAMERA_SIDE, le=MAX_CAMERA_WIDTH, description="the camera's image width, pixels"
    )
    camera_height: int = Field(
        default=240, ge=MIN_CAMERA_SIDE, le=MAX_CAMERA_HEIGHT, description="the camera's image height, pixels"
    )
    camera_rate: float = Field(
        default=5.0,
        ge=MIN_CAMERA_RATE_HZ,
        le=MAX_CAMERA_RATE_HZ,
        allow_inf_nan=False,
        description="camera frames a second (wall time), while someone reads them",
    )

    @field_validator("speed", mode="before")
    @classmethod
    def _parse_speed(cls, value: object) -> object:
        if isinstance(value, str) and value.strip().lower() == "max":
            return None
        return value

    @field_validator("speed")
    @classmethod
    def _check_speed(cls, value: float | None) -> float | None:
        if value is not None and not (0 < value <= 1000 and math.isfinite(value)):
            raise ValueError("speed must be a number in (0, 1000] or 'max'")
        return value

    @field_validator("robots", "obstacles")
    @classmethod
    def _robot_world_only(cls, value: int | None, info: ValidationInfo) -> int | None:
        if value is not None and info.data.get("world") not in ("robot", "soccer"):
            raise PydanticCustomError(
                "robot_world_only", f"only the robot world has {info.field_name}: add --world robot"
            )
        return value

    @property
    def robot_count(self) -> int:
        """How many robots the robot world has (1 unless ``robots`` says)."""
        return 1 if self.robots is None else self.robots

    @property
    def obstacle_count(self) -> int:
        """How many box obstacles the robot world has."""
        return DEFAULT_OBSTACLES if self.obstacles is None else self.obstacles
