"""What every world's simulator takes: flags ``--world/--seed/--speed`` and
``--camera-width/--camera-height/--camera-rate``, or ``SKYDECK_SIM_*`` variables.

A world's own options (the drone's ``--boxes``, the robot world's ``--robots``) are fields of
its settings class, a subclass of :class:`SimSettings` in the world's package; the table of
worlds (:mod:`sim_server.worlds`) names it. Pure settings: importing this loads no PyBullet.
"""

from __future__ import annotations

import math
import random

from pydantic import Field, ValidationError, field_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

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
    """Which world, its seed and speed, and its camera: what every world has."""

    model_config = SettingsConfigDict(env_prefix="SKYDECK_SIM_", extra="ignore")

    world: str | None = Field(default=None, description="which world (sim_server.worlds); None: the first")
    seed: int | None = Field(default=None, ge=0, le=2**32 - 1, description="None draws one")
    speed: float | None = Field(
        default=1.0, description="times real time; None is as fast as possible"
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

    @classmethod
    def own_options(cls) -> list[str]:
        """The fields of this world's settings that every world does not have (``boxes``)."""
        return [name for name in cls.model_fields if name not in SimSettings.model_fields]

    @classmethod
    def option_range(cls, name: str) -> tuple[float | None, float | None]:
        """The least and greatest value option ``name`` takes (``None``: no bound)."""
        metadata = cls.model_fields[name].metadata  # pydantic's Field(ge=..., le=...)
        low = next((item.ge for item in metadata if hasattr(item, "ge")), None)
        high = next((item.le for item in metadata if hasattr(item, "le")), None)
        return low, high

    @classmethod
    def options_given(cls, flags: dict[str, object]) -> list[str]:
        """Which of :meth:`own_options` are given: in ``flags`` (not ``None``) or in the
        environment (``SKYDECK_SIM_BOXES``). Another world's node uses it to refuse them."""
        own = cls.own_options()
        given = {name for name in own if flags.get(name) is not None}
        try:
            given |= cls().model_fields_set
        except ValidationError as error:  # a bad value is given all the same
            given |= {str(problem["loc"][0]) for problem in error.errors() if problem["loc"]}
        return [name for name in own if name in given]
