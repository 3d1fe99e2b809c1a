"""Where a ROS 2 launch description is evaluated: its launch configurations (the arguments'
values), the ROS namespace pushed so far, the file being read, the workspace and environment.

A group or an include works in a copy (:meth:`Context.scoped`), so what it sets stays in it.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from services.launch.arguments import LaunchArgument
from services.launch.ros2.packages import Workspace

__all__ = ["Context", "Declared"]


@dataclass
class Declared:
    """What the whole launch declares and uses, across its files (for ``--show-args`` and for a
    command-line argument nothing declares)."""

    arguments: dict[str, LaunchArgument] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


@dataclass
class Context:
    file: Path
    workspace: Workspace
    environ: Mapping[str, str]
    configurations: dict[str, str] = field(default_factory=dict)
    namespace: str = ""  # "" or an absolute namespace, "/robot1"
    declared: Declared = field(default_factory=Declared)
    depth: int = 0
    listing: bool = False  # --show-args: a required argument is taken as "", no executable is checked

    def scoped(self, *, file: Path | None = None) -> Context:
        """A copy for a group or an included file: its own configurations and namespace."""
        return dataclasses.replace(
            self,
            file=file or self.file,
            configurations=dict(self.configurations),
            depth=self.depth + (file is not None),
        )
