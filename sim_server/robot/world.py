"""The robot world: Neatos, box obstacles and a walking person in a closed room, in headless
PyBullet at 120 Hz (``PHYSICS_HZ`` in ``sim_server.robot.limits``).

Example::

    from sim_server.robot import RobotWorld, RobotWorldConfig

    world = RobotWorld(RobotWorldConfig(seed=1))
    world.set_cmd_vel(0, 0.2, 0.0)        # robot 0: 0.2 m/s ahead; re-send within 0.5 s
    world.step(PHYSICS_HZ)                # one second of sim time (120 steps)
    x, y, yaw = world.robot_pose(0)       # the truth; world.odometry(0) is what the wheels say
    ranges = world.scan(0)                # 360 beams, ranges[0] straight ahead
    world.close()

A robot moves only through its wheel motors (velocity control with a force limit) and the
contact of its wheels with the floor; the person is walked by a fixed constraint whose target
moves along the loop (the solver pushes the body there, and pushes a robot in the way). Nothing
is ever teleported. Each world owns its PyBullet client; not thread-safe.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

import pybullet as p

from sim_server.bullet import BulletWorld
from sim_server.geometry import yaw_of
from sim_server.robot.bodies import (
    WHEELS,
    create_floor,
    create_neato,
    create_obstacle,
    create_person,
    create_walls,
    person_pivot,
)
from sim_server.robot.drive import WheelOdometry, check_cmd_vel, wheel_speeds
from sim_server.robot.layout import Obstacle, PersonLoop, class_starts, place_obstacles
from sim_server.robot.limits import (
    CENTRE_OF_MASS_X_M,
    CMD_VEL_TIMEOUT_S,
    CONTROL_EVERY_STEPS,
    DEFAULT_OBSTACLES,
    MAX_CLASS_ROBOTS,
    MAX_OBSTACLES,
    MAX_ROBOTS,
    MAX_WHEEL_FORCE_N,
    PERSON_MAX_FORCE_N,
    PERSON_SPEED,
    PHYSICS_DT_S,
    PHYSICS_HZ,
    ROBOT_STARTS_M,
    SOLVER_ITERATIONS,
    WHEEL_RADIUS_M,
)
from sim_server.robot.scan import Laser
from sim_server.settings import draw_seed

__all__ = ["Bump", "RobotWorld", "RobotWorldConfig", "bumper_part"]

_WHEEL_TORQUE_NM = MAX_WHEEL_FORCE_N * WHEEL_RADIUS_M
_FRONT_DEG = 45.0
"""A bumper touch within this angle of straight ahead is a front bump, further round a side one."""
_SIDE_DEG = 120.0
"""Touches further back than this are behind the bumper (the Neato's bumper is its front half)."""


@dataclass(frozen=True, slots=True)
class RobotWorldConfig:
    """How to build a robot world. The same seed builds the same room; ``seed=None`` draws one
    (read it back from ``RobotWorld.seed``)."""

    seed: int | None = None
    robots: int = 1
    obstacles: int = DEFAULT_OBSTACLES
    students: tuple[str, ...] = ()
    """A class's room: one robot per student, on a grid (``robots`` is then their number)."""

    def __post_init__(self) -> None:
        if self.students:
            if not len(self.students) <= MAX_CLASS_ROBOTS:
                raise ValueError(f"{len(self.students)} students is more than a room holds ({MAX_CLASS_ROBOTS})")
            object.__setattr__(self, "robots", len(self.students))
        elif not 1 <= self.robots <= MAX_ROBOTS:
            raise ValueError(f"robots={self.robots} is outside [1, {MAX_ROBOTS}]")
        if not 0 <= self.obstacles <= MAX_OBSTACLES:
            raise ValueError(f"obstacles={self.obstacles} is outside [0, {MAX_OBSTACLES}]")


@dataclass(frozen=True, slots=True)
class Bump:
    """Which parts of a robot's bumper touch something (the Neato's four switches)."""

    left_front: bool = False
    left_side: bool = False
    right_front: bool = False
    right_side: bool = False

    def __bool__(self) -> bool:
        return self.left_front or self.left_side or self.right_front or self.right_side


_NO_BUMP = Bump()


@dataclass(slots=True)
class _Robot:
    body: int
    start: tuple[float, float, float]
    odometry: WheelOdometry = field(default_factory=WheelOdometry)
    command: tuple[float, float] = (0.0, 0.0)
    command_time_s: float = -math.inf
    driving: tuple[float, float] = (0.0, 0.0)
    """The command the motors run now (zero once the watchdog stopped them)."""


class RobotWorld(BulletWorld):
    """A closed room with ``config.robots`` Neatos, ``config.obstacles`` boxes and a person."""

    PHYSICS_HZ = PHYSICS_HZ

    def __init__(self, config: RobotWorldConfig | None = None) -> None:
        super().__init__()
        self.config = config or RobotWorldConfig()
        seed = self.config.seed
        self.seed: int = draw_seed() if seed is None else seed
        self.loop = PersonLoop()
        # Clear of every start a room may have (all four of a small room's: a seed builds the
        # same room for one robot or four), a class's robots on their grid.
        room_starts = class_starts(self.config.robots, self.loop) if self.config.students else ROBOT_STARTS_M
        self.starts = room_starts[: self.config.robots]
        self.obstacles: list[Obstacle] = place_obstacles(
            random.Random(self.seed), self.config.obstacles, self.loop, room_starts
        )
        self._laser = Laser(self._client)
        self._robots: list[_Robot] = []
        self._floor = self._person = self._person_constraint = -1
        self._walked_m = 0.0
        self._build()

    # -- lifecycle -----------------------------------------------------------------------------

    def reset(self) -> None:
        """Robots back at their starts (odometry zeroed, commands dropped), the person back at
        the start of the loop; the room stays as it is. The clock keeps running."""
        self._check_open()
        self._build()

    @property
    def robot_count(self) -> int:
        """How many robots the room has."""
        return len(self._robots)

    # -- inputs --------------------------------------------------------------------------------

    def set_cmd_vel(self, robot: int, linear_x: object, angular_z: object) -> tuple[float, float]:
        """Drive robot ``robot`` (0-based) at ``linear_x`` m/s ahead and ``angular_z`` rad/s
        counter-clockwise until CMD_VEL_TIMEOUT_S of sim time pass without another command.

        Returns the command as clamped to the robot's limits. Raises InvalidCommand for a value
        that is not a finite number (the robot then keeps its previous command, and stops when
        that one times out) and IndexError for a robot that does not exist.
        """
        self._check_open()
        state = self._robots[robot]
        state.command = check_cmd_vel(linear_x, angular_z)
        state.command_time_s = self.time_s
        return state.command

    # -- stepping ------------------------------------------------------------------------------

    def step(self, n: int = 1) -> None:
        """Advance the world by ``n`` physics steps of 1/PHYSICS_HZ s."""
        self._check_steps(n)
        client = self._client
        step_simulation = p.stepSimulation
        steps = self._steps
        for _ in range(n):
            step_simulation(physicsClientId=client)
            steps += 1
            self._steps = steps
            if steps % CONTROL_EVERY_STEPS == 0:  # after the step: odometry is never stale
                self._control(steps * PHYSICS_DT_S)

    def _control(self, now_s: float) -> None:
        """The control tick (30 Hz): watchdog and wheel motors, encoders, and the person's next stride."""
        client = self._client
        for robot in self._robots:
            command = robot.command if now_s - robot.command_time_s <= CMD_VEL_TIMEOUT_S else (0.0, 0.0)
            (left_angle, left_rate, *_), (right_angle, right_rate, *_) = p.getJointStates(
                robot.body, WHEELS, physicsClientId=client
            )
            robot.odometry.update(left_angle, right_angle, left_rate, right_rate)
            if command != robot.driving:
                robot.driving = command
                _drive_wheels(client, robot.body, command, (left_angle, right_angle))
        self.walk_person()

    def walk_person(self) -> None:
        """The person's next stride (each control tick): the target moves one tick ahead along
        the loop and the constraint pulls the legs there."""
        self._walked_m += PERSON_SPEED * CONTROL_EVERY_STEPS * PHYSICS_DT_S
        x, y, heading = self.loop.at(self._walked_m)
        p.changeConstraint(
            self._person_constraint,
            person_pivot(x, y),
            jointChildFrameOrientation=p.getQuaternionFromEuler((0.0, 0.0, heading)),
            maxForce=PERSON_MAX_FORCE_N,
            physicsClientId=self._client,
        )

    # -- read-out ------------------------------------------------------------------------------

    def robot_pose(self, robot: int) -> tuple[float, float, float]:
        """Where robot ``robot``'s base_link truly is: x, y (m) on the floor and heading (rad)."""
        self._check_open()
        (x, y, _), orientation = p.getBasePositionAndOrientation(
            self._robots[robot].body, physicsClientId=self._client
        )
        # PyBullet gives the centre of mass, which sits behind the axle; base_link is on it.
        yaw = yaw_of(orientation)
        return x - CENTRE_OF_MASS_X_M * math.cos(yaw), y - CENTRE_OF_MASS_X_M * math.sin(yaw), yaw

    def robot_tilt_deg(self, robot: int) -> float:
        """Angle between the robot's up axis and the vertical (0 while it stands on its wheels)."""
        self._check_open()
        qx, qy, _, _ = p.getBasePositionAndOrientation(
            self._robots[robot].body, physicsClientId=self._client
        )[1]
        return math.degrees(math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))))

    def robot_velocity(self, robot: int) -> tuple[float, float]:
        """Robot ``robot``'s true forward speed (m/s, body frame) and turn rate (rad/s)."""
        self._check_open()
        body = self._robots[robot].body
        (vx, vy, _), (_, _, wz) = p.getBaseVelocity(body, physicsClientId=self._client)
        _, _, yaw = self.robot_pose(robot)
        return vx * math.cos(yaw) + vy * math.sin(yaw), wz

    def robot_start(self, robot: int) -> tuple[float, float, float]:
        """Where robot ``robot`` starts (and its odom frame's origin): x, y, heading."""
        return self._robots[robot].start

    def odometry(self, robot: int) -> WheelOdometry:
        """What robot ``robot``'s wheel encoders say, in its odom frame: the live estimate, not a
        copy (read it; the world updates it)."""
        return self._robots[robot].odometry

    def command(self, robot: int) -> tuple[float, float]:
        """The (forward, turn) command robot ``robot``'s motors follow now (zero after the watchdog)."""
        return self._robots[robot].driving

    def scan(self, robot: int) -> list[float]:
        """Robot ``robot``'s laser scan now: SCAN_BEAMS ranges, ranges[0] straight ahead."""
        return self._laser.scan(*self.robot_pose(robot))

    def scan_from(self, x: float, y: float, yaw: float) -> list[float]:
        """The scan a laser at base_link pose (x, y, yaw) sees in the room as it is now."""
        self._check_open()
        return self._laser.scan(x, y, yaw)

    def bump(self, robot: int) -> Bump:
        """Which parts of robot ``robot``'s bumper touch something other than the floor now."""
        self._check_open()
        body = self._robots[robot].body
        contacts = [
            contact
            for contact in p.getContactPoints(bodyA=body, linkIndexA=-1, physicsClientId=self._client)
            if contact[2] != self._floor
        ]
        if not contacts:  # the usual case: the pose is read only when something touches
            return _NO_BUMP
        x, y, yaw = self.robot_pose(robot)
        touched = set()
        for contact in contacts:
            cx, cy = contact[5][0] - x, contact[5][1] - y  # the point on this robot
            touched.add(bumper_part(math.degrees(math.atan2(cy, cx) - yaw)))
        return Bump(**{part: True for part in touched if part})

    def person_pose(self) -> tuple[float, float, float]:
        """Where the person is: the midpoint between the legs (m) and the way they face (rad)."""
        self._check_open()
        (x, y, _), orientation = p.getBasePositionAndOrientation(
            self._person, physicsClientId=self._client
        )
        return x, y, yaw_of(orientation)

    # -- internals -----------------------------------------------------------------------------

    def _build(self) -> None:
        client = self._fresh_simulation()
        # Bullet's pyramid friction: with its default cone friction the wheels of a robot turning
        # on the spot slip by a degree or more at some headings, and odometry drifts with it.
        p.setPhysicsEngineParameter(
            numSolverIterations=SOLVER_ITERATIONS, enableConeFriction=0, physicsClientId=client
        )
        self._floor = create_floor(client)
        create_walls(client)
        for obstacle in self.obstacles:
            create_obstacle(client, obstacle)
        self._robots = []
        for sx, sy in self.starts:
            body = create_neato(client, sx, sy, 0.0)
            _drive_wheels(client, body, (0.0, 0.0), (0.0, 0.0))
            self._robots.append(_Robot(body=body, start=(sx, sy, 0.0)))
        self._walked_m = 0.0
        x, y, heading = self.loop.at(0.0)
        self._person, self._person_constraint = create_person(client, x, y, heading)
        self._control(self.time_s)  # the encoders' zero


def _drive_wheels(
    client: int, body: int, command: tuple[float, float], angles: tuple[float, float]
) -> None:
    """Set the wheel motors: velocity control towards the command's wheel rates, each with the
    motors' torque limit; stopped, they hold the wheels where they are (the motors' brake: a zero
    velocity target alone lets a robot creep a few millimetres a minute)."""
    if command == (0.0, 0.0):
        p.setJointMotorControlArray(
            body, WHEELS, p.POSITION_CONTROL, targetPositions=angles,
            forces=(_WHEEL_TORQUE_NM, _WHEEL_TORQUE_NM), physicsClientId=client,
        )  # fmt: skip
        return
    p.setJointMotorControlArray(
        body, WHEELS, p.VELOCITY_CONTROL, targetVelocities=wheel_speeds(*command),
        forces=(_WHEEL_TORQUE_NM, _WHEEL_TORQUE_NM), physicsClientId=client,
    )  # fmt: skip


def bumper_part(bearing_deg: float) -> str | None:
    """The Neato bumper switch that a touch at ``bearing_deg`` (counter-clockwise from straight
    ahead) presses: ``left_front``, ``left_side``, ``right_front``, ``right_side``, or None
    behind the bumper."""
    bearing = math.remainder(bearing_deg, 360.0)
    side = "left" if bearing >= 0.0 else "right"
    if abs(bearing) <= _FRONT_DEG:
        return f"{side}_front"
    if abs(bearing) <= _SIDE_DEG:
        return f"{side}_side"
    return None
