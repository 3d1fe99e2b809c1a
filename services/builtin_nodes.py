"""The nodes that ship with Skydeck, by the name ``skydeck run NAME`` and launch files use.

Each value is a module with ``main(argv: list[str]) -> int | None``. Both the CLI and the
launcher read this table, so neither imports the other for it.
"""

from __future__ import annotations

__all__ = ["BUILTIN_NODES"]

BUILTIN_NODES = {
    "sim": "sim_server.node",
    "perception": "services.perception.node",
    "control": "services.control.node",
    "ai": "services.ai.node",
    # The robot world's behaviours (services/behaviours/).
    "teleop": "services.behaviours.teleop",
    "drive_square": "services.behaviours.drive_square",
    "estop": "services.behaviours.estop",
    "wall_follower": "services.behaviours.wall_follower",
    "person_follower": "services.behaviours.person_follower",
    "obstacle_avoider": "services.behaviours.obstacle_avoider",
    "fsm": "services.behaviours.fsm",
    # The ROS 2 bridge (`skydeck bridge ros2`; `skydeck launch --ros2` starts it by this name).
    "ros2_bridge": "services.protocols.ros2.main",
}
