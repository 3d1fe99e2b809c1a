"""The soccer room's numbers: the ball and the robots' forward cameras. Pure constants: importing
this loads no PyBullet, so the core and the dashboard can read them.

The room, the robots and the person are the robot world's (``sim_server.robot.limits``).
"""

from __future__ import annotations

__all__ = [
    "BALL_ANGULAR_DAMPING",
    "BALL_FRICTION",
    "BALL_LINEAR_DAMPING",
    "BALL_MASS_KG",
    "BALL_RADIUS_M",
    "BALL_RESTITUTION",
    "BALL_ROLLING_FRICTION",
    "BALL_RGBA",
    "BALL_START_M",
    "CAMERA_FAR_M",
    "CAMERA_FORWARD_M",
    "CAMERA_HEIGHT_M",
    "CAMERA_NEAR_M",
    "CAMERA_PITCH_DEG",
    "CAMERA_VERTICAL_FOV_DEG",
]

# The ball: a size-3 football (19 cm across; a Neato's body is 10 cm tall), of a red-orange that
# nothing else in the room has, so a threshold in HSV finds it (OpenCV hue about 5).
BALL_RADIUS_M = 0.095
BALL_MASS_KG = 0.3
BALL_RGBA = (0.9, 0.22, 0.06, 1.0)
BALL_START_M = (1.4, 0.35)
"""Where the ball rests at the start: ahead of robot 1 (which faces +x from the origin), a
little to its left, inside the corridor the room keeps clear of boxes and away from the
person's walk."""
BALL_FRICTION = 0.6
BALL_ROLLING_FRICTION = 0.002
"""A rolling ball slows on the floor's rolling resistance (and damping) and comes to rest."""
BALL_RESTITUTION = 0.5
BALL_LINEAR_DAMPING = 0.05
BALL_ANGULAR_DAMPING = 0.05

# A robot's forward camera: at the front of its top, pitched down a little, with square pixels
# and this vertical field of view (the simulator's renderer's), so a ball on the floor a body
# length ahead is in the picture.
CAMERA_FORWARD_M = 0.12
CAMERA_HEIGHT_M = 0.16
CAMERA_PITCH_DEG = 10.0
CAMERA_VERTICAL_FOV_DEG = 60.0
CAMERA_NEAR_M = 0.05
CAMERA_FAR_M = 12.0
