"""One module under two names: a ROS name (``rclpy``, ``launch.actions``) loaded as the Skydeck
module that stands for it. Used by the ROS import finder (:mod:`services.ros.imports`) and by the
launcher's finder for a Python launch file's imports (:mod:`services.launch.ros2.python_file`)."""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import types

__all__ = ["AliasLoader"]


class AliasLoader(importlib.abc.Loader):
    """Loads a ROS name as the module it stands for: the same module object, which keeps its
    own ``__spec__`` (Python sets the alias's spec on it while loading; it is put back)."""

    def __init__(self, target: str) -> None:
        self.target = target
        self._own_spec: importlib.machinery.ModuleSpec | None = None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        module = importlib.import_module(self.target)
        self._own_spec = module.__spec__
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        module.__spec__ = self._own_spec
