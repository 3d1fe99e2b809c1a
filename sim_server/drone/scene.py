"""The PyBullet bodies of the world: ground, drone and boxes, with colours for the camera.

Everything is built from primitive shapes (no pybullet_data files), on the client id given.
"""

from __future__ import annotations

import pybullet as p

from sim_server.drone.airframe import Airframe
from sim_server.drone.boxes import BoxSpawn
from sim_server.drone.limits import BOX_MASS_KG, BOX_SIZE_M

__all__ = ["create_box", "create_drone", "create_ground"]

_GROUND_RGBA = (0.45, 0.62, 0.38, 1.0)
_HULL_RGBA = (0.15, 0.15, 0.18, 1.0)
_FRONT_ROTOR_RGBA = (0.95, 0.35, 0.2, 1.0)
_BACK_ROTOR_RGBA = (0.25, 0.55, 0.95, 1.0)
BOX_COLOURS = (
    (0.90, 0.60, 0.20, 1.0),
    (0.80, 0.25, 0.25, 1.0),
    (0.25, 0.45, 0.85, 1.0),
    (0.85, 0.80, 0.25, 1.0),
    (0.55, 0.35, 0.75, 1.0),
    (0.25, 0.70, 0.70, 1.0),
    (0.85, 0.45, 0.65, 1.0),
    (0.60, 0.45, 0.30, 1.0),
)
"""Box colours, repeated in this order for more than eight boxes."""

_GROUND_VISUAL_HALF_SIZE_M = 100.0


def create_ground(client: int) -> int:
    """An infinite static plane at z = 0 (drawn as a large flat tile)."""
    shape = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=client)
    visual = p.createVisualShape(
        p.GEOM_BOX,
        halfExtents=(_GROUND_VISUAL_HALF_SIZE_M, _GROUND_VISUAL_HALF_SIZE_M, 0.01),
        visualFramePosition=(0.0, 0.0, -0.01),
        rgbaColor=_GROUND_RGBA,
        physicsClientId=client,
    )
    return p.createMultiBody(0.0, shape, visual, physicsClientId=client)


def create_drone(
    client: int,
    airframe: Airframe,
    position: tuple[float, float, float],
    orientation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0),
) -> int:
    """The quadrotor: one rigid body with the airframe's mass and inertia and no damping."""
    hx, hy, hz = airframe.body_half_extents_m
    shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=(hx, hy, hz), physicsClientId=client)
    rotors = airframe.rotor_positions_m
    rotor_radius = 0.12
    visual = p.createVisualShapeArray(
        shapeTypes=[p.GEOM_BOX] + [p.GEOM_CYLINDER] * len(rotors),
        halfExtents=[(hx * 0.8, hy * 0.8, hz * 0.6)] + [(0.0, 0.0, 0.0)] * len(rotors),
        radii=[0.0] + [rotor_radius] * len(rotors),
        lengths=[0.0] + [0.02] * len(rotors),
        rgbaColors=[_HULL_RGBA]
        + [_FRONT_ROTOR_RGBA if rx > 0.0 else _BACK_ROTOR_RGBA for rx, _, _ in rotors],
        visualFramePositions=[(0.0, 0.0, 0.0)] + [(rx, ry, hz * 0.7) for rx, ry, _ in rotors],
        physicsClientId=client,
    )
    body = p.createMultiBody(
        airframe.mass_kg, shape, visual, position, orientation, physicsClientId=client
    )
    # Air drag is applied explicitly by the world; PyBullet's default damping would add to it.
    p.changeDynamics(
        body,
        -1,
        localInertiaDiagonal=airframe.inertia_kg_m2,
        linearDamping=0.0,
        angularDamping=0.0,
        physicsClientId=client,
    )
    return body


def create_box(client: int, spawn: BoxSpawn, rgba: tuple[float, float, float, float]) -> int:
    """One 2 m, 10 kg box at its spawn pose, free to fall."""
    half = BOX_SIZE_M / 2.0
    shape = p.createCollisionShape(
        p.GEOM_BOX, halfExtents=(half, half, half), physicsClientId=client
    )
    visual = p.createVisualShape(
        p.GEOM_BOX, halfExtents=(half, half, half), rgbaColor=rgba, physicsClientId=client
    )
    return p.createMultiBody(
        BOX_MASS_KG, shape, visual, spawn.position, spawn.orientation, physicsClientId=client
    )
