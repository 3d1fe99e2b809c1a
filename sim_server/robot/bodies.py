"""The PyBullet bodies of the robot world: floor, walls, box obstacles, Neatos and the person.

Built from primitive shapes on the client id given (no pybullet_data files). The Neato is one
multibody: the body (base), two driven wheels on revolute joints and a ball caster on a fixed
joint; only the wheels grip the floor.

Each body collides only with what it can touch (collision groups and masks; a pair filtered
out costs nothing in a step): the wheels and the caster with the floor; the Neato's body with
the floor (never touched, but its resting contact keeps a parked robot from creeping), the
walls, the boxes, other Neatos and the person; the person's legs (held clear of the floor by
their constraint, on a loop away from the walls and boxes) with the Neatos. The laser's rays
see everything but the floor (SCAN_MASK).
"""

from __future__ import annotations

import math

import pybullet as p

from sim_server.bullet import create_ground_plane
from sim_server.robot.layout import Obstacle
from sim_server.robot.limits import (
    BODY_BOTTOM_M,
    BODY_HEIGHT_M,
    CASTER_RADIUS_M,
    CASTER_X_M,
    CENTRE_OF_MASS_X_M,
    LASER_HEIGHT_M,
    LASER_HOUSING_RADIUS_M,
    LASER_HOUSING_TOP_M,
    LEG_HEIGHT_M,
    LEG_RADIUS_M,
    LEG_SPACING_M,
    OBSTACLE_HEIGHT_M,
    PERSON_MASS_KG,
    ROBOT_MASS_KG,
    ROBOT_RADIUS_M,
    ROOM_HALF_SIZE_M,
    WALL_HEIGHT_M,
    WALL_THICKNESS_M,
    WHEEL_FRICTION,
    WHEEL_RADIUS_M,
    WHEEL_SEPARATION_M,
    WHEEL_WIDTH_M,
)

__all__ = [
    "BODY_CENTRE_Z_M",
    "LEFT_WHEEL",
    "RIGHT_WHEEL",
    "SCAN_MASK",
    "WHEELS",
    "create_floor",
    "create_neato",
    "create_obstacle",
    "create_person",
    "create_walls",
]

_FLOOR_RGBA = (0.78, 0.74, 0.66, 1.0)
_WALL_RGBA = (0.92, 0.92, 0.95, 1.0)
_OBSTACLE_RGBA = (0.55, 0.42, 0.30, 1.0)
_BODY_RGBA = (0.12, 0.12, 0.14, 1.0)
_BUMPER_RGBA = (0.35, 0.55, 0.95, 1.0)
_WHEEL_RGBA = (0.05, 0.05, 0.05, 1.0)
_LEG_RGBA = (0.25, 0.30, 0.55, 1.0)

LEFT_WHEEL = 0
RIGHT_WHEEL = 1
WHEELS = (LEFT_WHEEL, RIGHT_WHEEL)
"""Joint (and link) indices of the driven wheels; the caster is link 2."""
_CASTER = 2
BODY_CENTRE_Z_M = BODY_BOTTOM_M + BODY_HEIGHT_M / 2.0
"""Height of the body's geometric centre above base_link (the floor)."""
_PERSON_CENTRE_Z_M = LEG_HEIGHT_M / 2.0 + 0.005  # legs just clear of the floor: no friction

# Collision groups (bits) and what each collides with.
_RAY = 1
"""The group Bullet gives ray tests (its default filter): a body is hit by rays only if its mask
has this bit, whatever the ray's mask says."""
_FLOOR = 2
_ROOM = 4
"""Walls and boxes."""
_NEATO = 8
"""A Neato's body, bumper and laser turret."""
_WHEELS = 16
"""A Neato's wheels and caster."""
_PERSON = 32
SCAN_MASK = _ROOM | _NEATO | _PERSON
"""What a laser ray can hit: everything but the floor (it never reaches it, level at
LASER_HEIGHT_M; leaving it out spares each ray a test)."""


def _collide(client: int, body: int, link: int, group: int, mask: int) -> None:
    p.setCollisionFilterGroupMask(body, link, group, mask | _RAY, physicsClientId=client)


def create_floor(client: int) -> int:
    """An infinite static plane at z = 0, drawn as a tile a little larger than the room."""
    floor = create_ground_plane(client, drawn_half_size_m=ROOM_HALF_SIZE_M + 2.0, drawn_thickness_m=0.01, rgba=_FLOOR_RGBA)
    _collide(client, floor, -1, _FLOOR, _WHEELS | _NEATO)
    return floor


def create_walls(client: int) -> list[int]:
    """Four static walls whose inner faces are at x, y = +-ROOM_HALF_SIZE_M.

    Each collides as a plane facing into the room (a laser ray costs a third of what it costs
    against a box, and nothing is ever outside) and is drawn as a box of WALL_THICKNESS_M.
    """
    half = ROOM_HALF_SIZE_M
    half_t = WALL_THICKNESS_M / 2.0
    along = half + WALL_THICKNESS_M  # long enough to close the corners
    walls = []
    for nx, ny in ((-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)):
        shape = p.createCollisionShape(
            p.GEOM_PLANE, planeNormal=(nx, ny, 0.0), physicsClientId=client
        )
        visual = p.createVisualShape(
            p.GEOM_BOX,
            halfExtents=(half_t if nx else along, half_t if ny else along, WALL_HEIGHT_M / 2.0),
            visualFramePosition=(-nx * half_t, -ny * half_t, WALL_HEIGHT_M / 2.0),
            rgbaColor=_WALL_RGBA,
            physicsClientId=client,
        )
        wall = p.createMultiBody(0.0, shape, visual, (-nx * half, -ny * half, 0.0), physicsClientId=client)
        _collide(client, wall, -1, _ROOM, _NEATO)
        walls.append(wall)
    return walls


def create_obstacle(client: int, obstacle: Obstacle) -> int:
    """One static box standing on the floor."""
    half = obstacle.size / 2.0
    extents = (half, half, OBSTACLE_HEIGHT_M / 2.0)
    shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=extents, physicsClientId=client)
    visual = p.createVisualShape(
        p.GEOM_BOX, halfExtents=extents, rgbaColor=_OBSTACLE_RGBA, physicsClientId=client
    )
    box = p.createMultiBody(
        0.0,
        shape,
        visual,
        (obstacle.x, obstacle.y, OBSTACLE_HEIGHT_M / 2.0),
        p.getQuaternionFromEuler((0.0, 0.0, obstacle.yaw)),
        physicsClientId=client,
    )
    _collide(client, box, -1, _ROOM, _NEATO)
    return box


def create_neato(client: int, x: float, y: float, yaw: float) -> int:
    """A Neato with base_link at (x, y) on the floor, facing ``yaw``; its body id. The wheels'
    joints are LEFT_WHEEL and RIGHT_WHEEL."""
    body_shape = p.createCollisionShapeArray(
        shapeTypes=[p.GEOM_CYLINDER, p.GEOM_CYLINDER],
        radii=[ROBOT_RADIUS_M, LASER_HOUSING_RADIUS_M],
        lengths=[BODY_HEIGHT_M, LASER_HOUSING_TOP_M - BODY_BOTTOM_M - BODY_HEIGHT_M],
        collisionFramePositions=[
            (0.0, 0.0, 0.0),
            (0.0, 0.0, (LASER_HOUSING_TOP_M + BODY_BOTTOM_M + BODY_HEIGHT_M) / 2.0 - BODY_CENTRE_Z_M),
        ],
        physicsClientId=client,
    )
    body_visual = p.createVisualShapeArray(
        shapeTypes=[p.GEOM_CYLINDER, p.GEOM_BOX, p.GEOM_CYLINDER],
        radii=[ROBOT_RADIUS_M, 0.0, LASER_HOUSING_RADIUS_M],
        lengths=[BODY_HEIGHT_M, 0.0, LASER_HOUSING_TOP_M - BODY_BOTTOM_M - BODY_HEIGHT_M],
        halfExtents=[(0.0, 0.0, 0.0), (0.03, ROBOT_RADIUS_M * 0.8, BODY_HEIGHT_M * 0.3), (0.0, 0.0, 0.0)],
        rgbaColors=[_BODY_RGBA, _BUMPER_RGBA, _BUMPER_RGBA],
        visualFramePositions=[
            (0.0, 0.0, 0.0),
            (ROBOT_RADIUS_M * 0.75, 0.0, BODY_HEIGHT_M * 0.3),  # a stripe on the front
            (0.0, 0.0, LASER_HEIGHT_M - BODY_CENTRE_Z_M),
        ],
        physicsClientId=client,
    )
    # A wheel touches the floor as a sphere of its radius: one contact point, as a narrow tyre
    # has, where a cylinder's contact line scrubs sideways when the robot turns in place.
    wheel_shape = p.createCollisionShape(p.GEOM_SPHERE, radius=WHEEL_RADIUS_M, physicsClientId=client)
    wheel_visual = p.createVisualShape(
        p.GEOM_CYLINDER,
        radius=WHEEL_RADIUS_M,
        length=WHEEL_WIDTH_M,
        rgbaColor=_WHEEL_RGBA,
        physicsClientId=client,
    )
    caster_shape = p.createCollisionShape(
        p.GEOM_SPHERE, radius=CASTER_RADIUS_M, physicsClientId=client
    )
    # A wheel's cylinder axis (its z) turned onto the body's +y: a positive joint rate rolls it
    # forward.
    axle = p.getQuaternionFromEuler((-math.pi / 2.0, 0.0, 0.0))
    wheel_z = WHEEL_RADIUS_M - BODY_CENTRE_Z_M
    caster_z = CASTER_RADIUS_M - BODY_CENTRE_Z_M
    half_track = WHEEL_SEPARATION_M / 2.0
    body = p.createMultiBody(
        baseMass=ROBOT_MASS_KG - 0.45,
        baseCollisionShapeIndex=body_shape,
        baseVisualShapeIndex=body_visual,
        basePosition=(x, y, BODY_CENTRE_Z_M),
        baseOrientation=p.getQuaternionFromEuler((0.0, 0.0, yaw)),
        baseInertialFramePosition=(CENTRE_OF_MASS_X_M, 0.0, 0.0),
        linkMasses=[0.2, 0.2, 0.05],
        linkCollisionShapeIndices=[wheel_shape, wheel_shape, caster_shape],
        linkVisualShapeIndices=[wheel_visual, wheel_visual, -1],
        linkPositions=[(0.0, half_track, wheel_z), (0.0, -half_track, wheel_z), (CASTER_X_M, 0.0, caster_z)],
        linkOrientations=[axle, axle, (0.0, 0.0, 0.0, 1.0)],
        linkInertialFramePositions=[(0.0, 0.0, 0.0)] * 3,
        linkInertialFrameOrientations=[(0.0, 0.0, 0.0, 1.0)] * 3,
        linkParentIndices=[0, 0, 0],
        linkJointTypes=[p.JOINT_REVOLUTE, p.JOINT_REVOLUTE, p.JOINT_FIXED],
        linkJointAxis=[(0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0)],
        physicsClientId=client,
    )
    # Only the wheels grip; the ball caster rolls (no friction), the body slides along walls.
    for wheel in (LEFT_WHEEL, RIGHT_WHEEL):
        p.changeDynamics(body, wheel, lateralFriction=WHEEL_FRICTION, physicsClientId=client)
    p.changeDynamics(body, _CASTER, lateralFriction=0.0, physicsClientId=client)
    p.changeDynamics(body, -1, lateralFriction=0.3, physicsClientId=client)
    _collide(client, body, -1, _NEATO, _FLOOR | _ROOM | _NEATO | _PERSON)
    for link in (LEFT_WHEEL, RIGHT_WHEEL, _CASTER):
        _collide(client, body, link, _WHEELS, _FLOOR)
    return body


def create_person(client: int, x: float, y: float, heading: float) -> tuple[int, int]:
    """The person: two legs side by side, one rigid body, held up and walked by a fixed
    constraint (see ``RobotWorld``). Returns (body, constraint)."""
    half_spacing = LEG_SPACING_M / 2.0
    legs = [(0.0, half_spacing, 0.0), (0.0, -half_spacing, 0.0)]
    shape = p.createCollisionShapeArray(
        shapeTypes=[p.GEOM_CYLINDER, p.GEOM_CYLINDER],
        radii=[LEG_RADIUS_M, LEG_RADIUS_M],
        lengths=[LEG_HEIGHT_M, LEG_HEIGHT_M],
        collisionFramePositions=legs,
        physicsClientId=client,
    )
    visual = p.createVisualShapeArray(
        shapeTypes=[p.GEOM_CYLINDER, p.GEOM_CYLINDER],
        radii=[LEG_RADIUS_M, LEG_RADIUS_M],
        lengths=[LEG_HEIGHT_M, LEG_HEIGHT_M],
        rgbaColors=[_LEG_RGBA, _LEG_RGBA],
        visualFramePositions=legs,
        physicsClientId=client,
    )
    orientation = p.getQuaternionFromEuler((0.0, 0.0, heading))
    body = p.createMultiBody(
        PERSON_MASS_KG,
        shape,
        visual,
        (x, y, _PERSON_CENTRE_Z_M),
        orientation,
        physicsClientId=client,
    )
    _collide(client, body, -1, _PERSON, _NEATO)
    constraint = p.createConstraint(
        body,
        -1,
        -1,
        -1,
        p.JOINT_FIXED,
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 0.0),
        (x, y, _PERSON_CENTRE_Z_M),
        childFrameOrientation=orientation,
        physicsClientId=client,
    )
    return body, constraint


def person_pivot(x: float, y: float) -> tuple[float, float, float]:
    """Where the constraint holds the person's centre when they stand at (x, y)."""
    return (x, y, _PERSON_CENTRE_Z_M)
