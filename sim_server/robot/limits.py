"""The robot world's numbers in one place: the room, the Neato, its sensors, the person, the rates.

The physics, the command checks, the node and the core's ``/api/config`` (which the dashboard
reads) all import these, so a limit a user sees in a message is the one the physics enforces.
Pure constants: importing this module loads no PyBullet.

Frames: x forward, y left, z up. ``base_link`` is on the floor, midway between the wheels.
"""

from __future__ import annotations

import math

# -- the room -----------------------------------------------------------------------------------
ROOM_HALF_SIZE_M = 4.0
"""The walls' inner faces are at x = +-4 m and y = +-4 m."""
WALL_THICKNESS_M = 0.1
WALL_HEIGHT_M = 0.5
CORRIDOR_HALF_WIDTH_M = 0.6
"""From robot 1's start to the +x wall, |y| below this stays free of obstacles and of the person."""
WALL_LANE_M = 1.0
"""Obstacles keep this far from every wall, so a wall can be followed all round the room."""

# -- obstacles ----------------------------------------------------------------------------------
DEFAULT_OBSTACLES = 4
MAX_OBSTACLES = 8
OBSTACLE_SIZE_M = (0.3, 0.6)
"""Side of a (square) box obstacle, drawn per box."""
OBSTACLE_HEIGHT_M = 0.4
OBSTACLE_GAP_M = 0.6
"""Least free space between two obstacles, or an obstacle and a start or the person's path:
wide enough for the robot to pass."""

# -- the robot (a Neato Botvac) -----------------------------------------------------------------
ROBOT_RADIUS_M = 0.165
"""0.33 m across."""
ROBOT_MASS_KG = 3.6
WHEEL_RADIUS_M = 0.035
WHEEL_SEPARATION_M = 0.235
"""Distance between the two driven wheels' contact points."""
WHEEL_WIDTH_M = 0.02
BODY_BOTTOM_M = 0.015
"""Ground clearance of the body."""
BODY_HEIGHT_M = 0.09
CASTER_RADIUS_M = 0.015
CASTER_X_M = -0.12
"""The ball caster behind the axle (the body's centre of mass sits between them)."""
CENTRE_OF_MASS_X_M = -0.04
MAX_WHEEL_FORCE_N = 4.0
"""The wheel motors' force limit at the tyre: about 2.2 m/s^2 of acceleration."""
WHEEL_FRICTION = 1.0

MAX_LINEAR_SPEED = 0.3
"""m/s, forward and back; faster commands are clamped."""
MAX_ANGULAR_SPEED = 2.0
"""rad/s, either way; faster commands are clamped."""
CMD_VEL_TIMEOUT_S = 0.5
"""Sim seconds without a /cmd_vel before the robot stops (the watchdog)."""

# -- the laser (base_laser_link) ----------------------------------------------------------------
LASER_HEIGHT_M = 0.12
"""base_link -> base_laser_link: straight up, no rotation."""
LASER_HOUSING_RADIUS_M = 0.05
"""The turret on top of the body (other robots' lasers see it)."""
LASER_HOUSING_TOP_M = 0.14
SCAN_BEAMS = 360
SCAN_ANGLE_INCREMENT = math.tau / SCAN_BEAMS
RANGE_MIN_M = 0.2
RANGE_MAX_M = 5.0
NO_RETURN = 0.0
"""What a beam with no return reads, as the Neato driver writes it."""

# -- the person ---------------------------------------------------------------------------------
LEG_RADIUS_M = 0.1
LEG_HEIGHT_M = 0.8
LEG_SPACING_M = 0.3
"""Between the two legs' centres, side by side across the walking direction."""
PERSON_SPEED = 0.25
"""m/s along the loop (a slow walk the robot, at 0.3 m/s, can keep up with)."""
PERSON_LOOP_CENTRE_M = (-0.6, 2.2)
PERSON_LOOP_RADII_M = (2.0, 0.8)
"""The person walks this ellipse counter-clockwise: x in [-2.6, 1.4], y in [1.4, 3.0]."""
PERSON_MASS_KG = 30.0
PERSON_MAX_FORCE_N = 400.0
"""What the constraint that walks the person may push with (a robot in the way is shoved)."""

# -- several robots -----------------------------------------------------------------------------
MAX_ROBOTS = 4
ROBOT_STARTS_M = ((0.0, 0.0), (0.0, -1.5), (-1.5, 0.0), (-1.5, -1.5))
"""Where robot 1, 2, ... start, all facing +x; kept clear whatever the number of robots, so a
seed builds the same room for one robot or four."""
MAX_CLASS_ROBOTS = 40
"""A class's room (``skydeck class``: one robot per student, named): its robots stand on a grid
(:func:`sim_server.robot.layout.class_starts`), as far apart as their number allows."""
CLASS_GRID_PITCHES_M = (2.0, 1.6, 1.3, 1.1, 1.0, 0.9, 0.8)
"""The grid's spacings tried, widest first: the first that holds the class is used."""
CLASS_PERSON_CLEARANCE_M = 0.7
"""A class's start keeps this far from the person's walk (the legs and a robot pass between)."""

# -- rates (sim time) -----------------------------------------------------------------------------
PHYSICS_HZ = 120
"""The robot world's physics steps per sim second: half the drone world's 240 Hz. A Neato at
0.3 m/s moves 2.5 mm a step, its wheels' contact with the floor and its motors' 30 Hz commands
are as steady as at 240 Hz (the drive and behaviour tests' figures hold), and a sim second costs
half the steps."""
PHYSICS_DT_S = 1.0 / PHYSICS_HZ
CONTROL_EVERY_STEPS = PHYSICS_HZ // 30
"""Wheel commands, watchdog, encoders and the person's walk update at 30 Hz."""
ODOM_EVERY_STEPS = PHYSICS_HZ // 30
"""/odom, /tf, /bump and /clock: 30 Hz."""
TRUTH_EVERY_STEPS = PHYSICS_HZ // 10
"""/simulator/robots and /simulator/people: 10 Hz."""
SCAN_EVERY_STEPS = PHYSICS_HZ // 5
"""/scan: 5 Hz, as the Neato's spinning laser."""
SOLVER_ITERATIONS = 10
"""Fewer than PyBullet's 50: the robot drives, turns and stops the same (the tests' figures hold),
and a step costs two thirds as much."""
