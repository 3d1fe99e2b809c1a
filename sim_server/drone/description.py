"""The drone world as its clients see it before it runs (``GET /api/config``'s ``worlds.drone``):
the arena's numbers, and the names of the simulator's topics and the workshop nodes' (control,
perception, the AI) that run beside it. Pure constants: importing this loads no PyBullet."""

from __future__ import annotations

from sim_server.description import WorldDescription
from sim_server.drone import limits

__all__ = ["DESCRIPTION"]

DESCRIPTION = WorldDescription(
    constants={
        "arena_half_size_m": limits.ARENA_HALF_SIZE_M,
        "fly_half_size_m": limits.FLY_HALF_SIZE_M,
        "box_size_m": limits.BOX_SIZE_M,
        "start_xy_m": list(limits.START_XY_M),
    },
    topics={
        # the simulator's
        "pose": "/drone/pose",
        "state": "/drone/state",
        "setpoint": "/drone/setpoint",
        "cmd_vel": "/drone/cmd_vel",
        "boxes": "/simulator/boxes",
        # the workshop nodes'
        "perception_boxes": "/perception/boxes",
        "control_state": "/control/state",
        "ai_status": "/ai/status",
    },
    services={
        "take_off": "/control/take_off",
        "fly": "/control/fly",
        "land": "/control/land",
        "ai_start": "/ai/start",
        "ai_stop": "/ai/stop",
    },
)
