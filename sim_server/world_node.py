"""What every world's simulator node shares: its name, ``/clock``, the world's identity on
``/simulator/world``, ``/simulator/reset``, the camera (:mod:`sim_server.camera_stream`), the
world's options as read-only parameters, throttled warnings, and the one physics loop that
keeps pace with the wall clock (or runs flat out at ``--speed max``).

A world's node (``sim_server.drone.node.DroneSimNode``, ``sim_server.robot.node.RobotSimNode``)
adds its own topics and fills in the hooks: ``PUBLISH_EVERY_STEPS``, ``WORLD_NAME``,
``_publish_tick``, ``_reset_world``, ``_publish_build``, ``_world_fields`` and
``_render_camera``. Its options are its settings class's own fields (a subclass of
:class:`~sim_server.settings.SimSettings`).
"""

from __future__ import annotations

import asyncio
import math
import secrets
import time
from collections import defaultdict
from collections.abc import Callable
from typing import Any, ClassVar, Generic, Protocol, TypeVar

from pydantic import ValidationError

from services.runtime import Node, NodeSettings
from services.runtime.lockstep import agent as lockstep
from services.runtime.lockstep.frames import StepWhat
from services.runtime.parameters import InvalidParameterValueException
from services.runtime.settings import node_settings
from shared_models.builtin_interfaces import Time, split_seconds
from shared_models.rcl_interfaces import IntegerRange, ParameterDescriptor
from shared_models.ros_workshop import SimWorld
from shared_models.std_msgs import Header
from shared_models.std_srvs import Trigger, TriggerRequest, TriggerResponse
from sim_server.camera_stream import CameraStream
from sim_server.settings import SimSettings, draw_seed

__all__ = ["DEFAULT_PORT", "SteppedWorld", "WorldNode"]

S = TypeVar("S", bound=SimSettings)

DEFAULT_PORT = 8001
# Falling further behind real time than this resets the pace instead of bursting to catch up.
_MAX_LAG_S = 0.25
_WARN_EVERY_S = 5.0


def _option_descriptor(sim: SimSettings, name: str) -> ParameterDescriptor:
    """A world's own option (``boxes``) as a read-only parameter: its field's description and,
    for a whole number, its range."""
    low, high = sim.option_range(name)
    ranges: list[IntegerRange] = []
    if isinstance(getattr(sim, name), int) and isinstance(low, int) and isinstance(high, int):
        ranges = [IntegerRange(from_value=low, to_value=high)]
    return ParameterDescriptor(
        read_only=True, description=type(sim).model_fields[name].description or name, integer_range=ranges
    )


class SteppedWorld(Protocol):
    """What the loop needs of a world."""

    seed: int

    @property
    def time_s(self) -> float: ...

    @property
    def steps(self) -> int: ...

    def step(self, n: int = 1) -> None: ...

    def close(self) -> None: ...


class WorldNode(Node, Generic[S]):
    """The simulator node's common part, for a world whose settings are ``S``; the physics loop
    runs in the node's event loop, in chunks of ``PUBLISH_EVERY_STEPS`` physics steps,
    publishing after each."""

    PUBLISH_EVERY_STEPS: ClassVar[int]
    WORLD_NAME: ClassVar[str]

    def __init__(self, sim: S, settings: NodeSettings | None, build: Callable[[S], SteppedWorld]) -> None:
        super().__init__("sim", settings=settings or node_settings().with_default_port(DEFAULT_PORT))
        self.sim = sim
        self.sim = self._declare_world_parameters()
        self.world = build(self.sim)
        self.resets = 0
        self._last_warning: defaultdict[str, float] = defaultdict(lambda: -math.inf)
        self.world_publisher = self.create_publisher(SimWorld, "/simulator/world", 1, latched=True)
        self.clock_publisher = self.create_publisher(Time, "/clock", 10)
        self.camera = CameraStream(self, self.sim, self._render_camera, self.header)
        self.create_service(Trigger, "/simulator/reset", self.on_reset)

    # -- hooks --------------------------------------------------------------------------------

    def _publish_tick(self, steps: int) -> None:
        """Publish the world's own topics that are due after the physics reached ``steps``
        (``/clock`` is published beside them, by :meth:`_publish_clock`)."""
        raise NotImplementedError

    def _reset_world(self) -> str:
        """Reset the world's physics; the reset's answer, after 'world reset: '."""
        raise NotImplementedError

    def _publish_build(self) -> None:
        """Publish what a new build of the world changes (after its new identity)."""
        raise NotImplementedError

    def _world_fields(self) -> dict[str, Any]:
        """The world-specific fields of ``/simulator/world`` (its sizes; ``world`` is
        ``WORLD_NAME``)."""
        raise NotImplementedError

    def _render_camera(self, width: int, height: int) -> bytes:
        """One image of the world's camera, ``rgb8`` (:func:`sim_server.camera.render_rgb`)."""
        raise NotImplementedError

    # -- common -------------------------------------------------------------------------------

    def _declare_world_parameters(self) -> S:
        """The world's options as read-only parameters (``skydeck param get /sim seed``); an
        override (``--ros-args -p seed:=5``) wins over the flag, as for any parameter."""
        sim = self.sim
        seed = self.declare_parameter(
            "seed",
            draw_seed() if sim.seed is None else sim.seed,
            ParameterDescriptor(
                read_only=True,
                description="the world's random seed (drawn when not given): the same seed, the same world",
                integer_range=[IntegerRange(from_value=0, to_value=2**32 - 1)],
            ),
        ).value
        speed = self.declare_parameter(
            "speed",
            "max" if sim.speed is None else sim.speed,
            ParameterDescriptor(read_only=True, dynamic_typing=True, description="times real time, or 'max'"),
        ).value
        own = {name: self.declare_parameter(name, getattr(sim, name), _option_descriptor(sim, name)).value
               for name in sim.own_options()}  # fmt: skip
        try:
            return type(sim)(**{**sim.model_dump(exclude_unset=True), "seed": seed, "speed": speed, **own})
        except ValidationError as error:
            problem = error.errors()[0]
            raise InvalidParameterValueException(
                f"{self.get_name()}: parameter '{problem['loc'][0]}': {problem['msg']}"
            ) from None

    def _announce(self, what: str) -> None:
        self.world_info = self._publish_world()
        speed = "max" if self.sim.speed is None else f"{self.sim.speed:g}x"
        self.get_logger().info(
            "%s world %s: seed %d, %s, speed %s",
            self.WORLD_NAME, self.world_info.id, self.world.seed, what, speed,
        )  # fmt: skip

    def on_reset(self, request: TriggerRequest) -> TriggerResponse:
        what = self._reset_world()
        self.resets += 1
        # The new identity first, then what it changed: a reader of both (the AI) learns of the
        # new world before it sees the new world's data.
        self.world_info = self._publish_world()
        self._publish_build()
        self.get_logger().info("world %s: reset %d: %s", self.world_info.id, self.resets, what)
        return TriggerResponse(success=True, message=f"world reset: {what} (world {self.world_info.id})")

    def warn(self, kind: str, text: str) -> None:
        """Log ``text`` as a warning, at most once every few seconds per ``kind``: a bad stream
        would otherwise log at its own rate."""
        now = time.monotonic()
        if now - self._last_warning[kind] >= _WARN_EVERY_S:
            self._last_warning[kind] = now
            self.get_logger().warning("%s", text)

    def header(self, frame_id: str = "map") -> Header:
        """A header stamped with the world's sim time."""
        return Header(stamp=Time.from_seconds(self.world.time_s), frame_id=frame_id)

    def _publish_clock(self) -> None:
        """``/clock``: the world's sim time now."""
        sec, nanosec = split_seconds(self.world.time_s)
        self.clock_publisher.publish_built(lambda: Time(sec=sec, nanosec=nanosec))

    def _publish_world(self) -> SimWorld:
        """Announce a new build of the world: a random id that no other build has (progress
        saved for one build, the AI's, must never be taken for another, even of the same seed)."""
        info = SimWorld(
            header=self.header(),
            id=secrets.token_hex(8),
            seed=self.world.seed,
            build=self.resets,
            world=self.WORLD_NAME,
            **self._world_fields(),
        )
        self.world_publisher.publish(info)
        return info

    # -- the physics loop ---------------------------------------------------------------------

    async def start(self) -> None:
        await super().start()
        self._physics = asyncio.get_running_loop().create_task(self._run_physics())

    async def stop(self) -> None:
        physics = getattr(self, "_physics", None)
        if physics is not None:
            physics.cancel()
            await asyncio.gather(physics, return_exceptions=True)
        await super().stop()
        self.world.close()

    async def _run_physics(self) -> None:
        """Step in chunks of one publishing period, publish, and keep pace with the wall clock;
        in a lockstep run, step when the run's coordinator says (:meth:`_lockstep_step`)."""
        if self.settings.lockstep_url:
            lockstep.set_stepper(self._lockstep_step)
            return
        world = self.world
        speed = self.sim.speed
        every = self.PUBLISH_EVERY_STEPS
        sim_origin_s = world.time_s
        wall_origin_s = time.monotonic()
        self._publish_clock()
        self._publish_tick(world.steps)
        while True:
            world.step(every - world.steps % every)
            self._publish_clock()
            self._publish_tick(world.steps)
            if speed is None:
                await asyncio.sleep(0)  # as fast as possible, but let sockets and callbacks run
                continue
            ahead_s = wall_origin_s + (world.time_s - sim_origin_s) / speed - time.monotonic()
            if ahead_s > 0:
                await asyncio.sleep(ahead_s)
            else:
                if -ahead_s > _MAX_LAG_S:
                    self.warn(
                        "lag", f"physics is {-ahead_s:.2f} s behind real time at speed {speed:g}x"
                    )
                    sim_origin_s, wall_origin_s = world.time_s, time.monotonic()
                await asyncio.sleep(0)

    def _lockstep_step(self, what: StepWhat) -> float:
        """One step of a lockstep run: ``advance`` steps a publishing period, ``start`` does not;
        both publish (the run's agents move the nodes' clocks once the step's messages are in)."""
        world = self.world
        if what == "advance":
            world.step(self.PUBLISH_EVERY_STEPS - world.steps % self.PUBLISH_EVERY_STEPS)
        self._publish_clock()
        self._publish_tick(world.steps)
        return world.time_s
