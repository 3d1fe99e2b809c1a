"""The drone world's numbers in one place: arena bounds, speed limits, timings, boxes.

The controller, the command checks, the simulator node and the workshop's nodes (control, the
AI) all import these, so a limit that a user sees in an error message is the limit the physics
enforces. Pure constants: importing this module loads no PyBullet.
"""

from __future__ import annotations

import math

# -- clock ------------------------------------------------------------------------------------
PHYSICS_HZ = 240
PHYSICS_DT_S = 1.0 / PHYSICS_HZ
GRAVITY_M_S2 = 9.81

# -- arena --------------------------------------------------------------------------------------
ARENA_HALF_SIZE_M = 15.0
"""Boxes spawn with their centres at |x|, |y| <= this."""
FLY_HALF_SIZE_M = 20.0
"""Setpoints may go this far out (the arena plus a margin to fly around the outer boxes)."""
CEILING_M = 50.0
"""Highest setpoint altitude accepted."""
START_XY_M = (0.0, 0.0)
"""Where the drone stands after start and after every reset."""
ON_GROUND_Z_M = 0.1
"""At or below this altitude the drone counts as on the ground (the workshop's take-off check)."""

# -- drone limits -------------------------------------------------------------------------------
MAX_SPEED_XY = 8.0
"""Horizontal speed limit, m/s."""
MAX_SPEED_Z = 3.0
"""Vertical speed limit, m/s, up and down."""
MAX_YAW_RATE = math.radians(90.0)
"""Yaw rate limit, rad/s."""
MAX_TILT_DEG = 35.0
"""The controller never asks for more tilt than this."""
HORIZONTAL_CONTROL_MIN_Z_M = 0.3
"""Below this altitude the drone ignores horizontal commands and climbs or descends level."""

# -- command streams ----------------------------------------------------------------------------
STREAM_TIMEOUT_S = 0.5
"""A setpoint older than this (sim time) ends offboard control; an older cmd_vel counts as zero."""

# -- boxes --------------------------------------------------------------------------------------
DEFAULT_BOXES = 8
MAX_BOXES = 30
"""More boxes than this no longer fit the arena with the required spacing."""
BOX_SIZE_M = 2.0
BOX_MASS_KG = 10.0
BOX_MIN_START_DISTANCE_M = 4.0
"""Landed box centres are more than this far (horizontally) from the drone's start."""
BOX_TUMBLE_ALLOWANCE_M = 2.0
"""How far a box may roll when it lands on a corner and tips over (1.7 m at most, measured
over 480 drops). Boxes spawn this much further from the start, so they land clear of it."""
BOX_SPAWN_Z_M = (4.0, 8.0)
