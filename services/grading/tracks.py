"""A recorded run as the criteria read it: where things were, in sim time.

    tracks = read_tracks(Path("run.mcap"))
    tracks.robot[-1]          # Pose(t=40.0, x=..., y=..., yaw=...): the truth, robot 1
    tracks.bumps              # the ticks a bumper switch was pressed

Everything comes from the world's truth topics (``/simulator/robots``, ``/simulator/people``,
``/simulator/obstacles``, ``/drone/pose``, ``/simulator/boxes``) and a few of the robot's own
(``/bump``, ``/odom``, ``fsm/state``). Times are header stamps; a message without a header (a
bump, a command) takes the sim time of the last ``/clock`` recorded before it, which in a
lockstep run is the same in every run of the same programs and seed.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from services.bag.reader import BagReader
from services.grading.geometry import position_at
from services.grading.shapes import Box, BumpEvent, Pose

__all__ = ["Box", "BumpEvent", "Pose", "Tracks", "read_tracks"]

_TOPICS = (
    "/clock", "/simulator/world", "/simulator/robots", "/simulator/people", "/simulator/obstacles",
    "/bump", "/odom", "/cmd_vel", "/fsm/state", "/drone/pose", "/simulator/boxes", "/rosout",
)  # fmt: skip


@dataclass
class Tracks:
    """A run, as the criteria read it (see the module docstring)."""

    world: str = ""
    seed: int = 0
    end_s: float = 0.0
    robot: list[Pose] = field(default_factory=list)
    odom: list[Pose] = field(default_factory=list)
    people: list[Pose] = field(default_factory=list)
    obstacles: list[Box] = field(default_factory=list)
    bumps: list[BumpEvent] = field(default_factory=list)
    commands: list[tuple[float, float, float]] = field(default_factory=list)
    """(t, forward m/s, turn rad/s) of every ``/cmd_vel``."""
    states: list[tuple[float, str]] = field(default_factory=list)
    """``fsm/state`` changes."""
    drone: list[Pose] = field(default_factory=list)
    boxes: list[Box] = field(default_factory=list)
    """The drone world's boxes, where they came to rest."""
    logs: list[tuple[float, str, str]] = field(default_factory=list)
    """(t, node, text) of each ``/rosout`` line."""

    @property
    def walls(self) -> list[Box]:
        return [box for box in self.obstacles if box.kind == "wall"]


def _stamp(header: dict[str, Any]) -> float:
    stamp = header["stamp"]
    return float(stamp["sec"]) + float(stamp["nanosec"]) * 1e-9


def _yaw(q: dict[str, float]) -> float:
    return math.atan2(2.0 * (q["w"] * q["z"] + q["x"] * q["y"]), 1.0 - 2.0 * (q["y"] ** 2 + q["z"] ** 2))


def _pose(t: float, pose: dict[str, Any]) -> Pose:
    p = pose["position"]
    return Pose(t, p["x"], p["y"], _yaw(pose["orientation"]), p.get("z", 0.0))


class _Reader:
    """Folds the recording's messages, in the order recorded, into :class:`Tracks`."""

    def __init__(self) -> None:
        self.tracks = Tracks()
        self.clock_s = 0.0

    def take(self, topic: str, message: dict[str, Any]) -> None:
        tracks = self.tracks
        if topic == "/clock":
            self.clock_s = float(message["sec"]) + float(message["nanosec"]) * 1e-9
            tracks.end_s = max(tracks.end_s, self.clock_s)
        elif topic == "/simulator/world":
            tracks.world, tracks.seed = message.get("world", ""), int(message.get("seed", 0))
        elif topic == "/simulator/robots" and message["poses"]:
            tracks.robot.append(_pose(_stamp(message["header"]), message["poses"][0]))
        elif topic == "/simulator/people" and message["poses"]:
            tracks.people.append(_pose(_stamp(message["header"]), message["poses"][0]))
        elif topic == "/odom":
            tracks.odom.append(_pose(_stamp(message["header"]), message["pose"]["pose"]))
        elif topic == "/simulator/obstacles":
            tracks.obstacles = [_marker_box(marker) for marker in message["markers"]]
        elif topic == "/bump":
            parts = tuple(part for part, pressed in message.items() if pressed)
            if parts:  # where: once the robot's track is whole (read_tracks)
                tracks.bumps.append(BumpEvent(self.clock_s, math.nan, math.nan, parts))
        elif topic == "/cmd_vel":
            tracks.commands.append((self.clock_s, message["linear"]["x"], message["angular"]["z"]))
        elif topic == "/fsm/state":
            if not tracks.states or tracks.states[-1][1] != message["data"]:
                tracks.states.append((self.clock_s, message["data"]))
        elif topic == "/drone/pose":
            tracks.drone.append(_pose(_stamp(message["header"]), message["pose"]))
        elif topic == "/simulator/boxes":
            tracks.boxes = [
                Box(p["position"]["x"], p["position"]["y"], 2.0, 2.0, _yaw(p["orientation"]), "box")
                for p in message["poses"]
            ]
        elif topic == "/rosout":
            tracks.logs.append((self.clock_s, message.get("name", ""), message.get("msg", "")))


def _marker_box(marker: dict[str, Any]) -> Box:
    pose, scale = marker["pose"], marker["scale"]
    kind = "wall" if marker.get("ns") == "walls" else "obstacle"
    return Box(pose["position"]["x"], pose["position"]["y"], scale["x"], scale["y"], _yaw(pose["orientation"]), kind)


def read_tracks(path: Path) -> Tracks:
    """The tracks of the run recorded at ``path`` (BagFileError if it cannot be read)."""
    reader = _Reader()
    with BagReader(path) as bag:
        for message in bag.messages(_TOPICS):
            reader.take(message.topic, json.loads(message.frame))
    tracks = reader.tracks
    for series in (tracks.robot, tracks.people, tracks.odom, tracks.drone):
        series.sort(key=lambda pose: pose.t)  # stamped: the order the world made them in
    if tracks.robot:
        tracks.bumps = [
            BumpEvent(bump.t, *position_at(tracks.robot, bump.t), bump.parts) for bump in tracks.bumps
        ]
    return tracks
