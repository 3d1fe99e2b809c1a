"""The packages a ROS 2 launch file names (``package='py_pubsub'``, ``$(find-pkg-share
py_pubsub)``, ``get_package_share_directory('py_pubsub')``), found in the launch's workspaces.

Skydeck runs a workspace from its sources, never from an ``install/`` tree, so a package's
*share directory* is its source folder: where colcon's ``data_files`` copy ``launch/`` and
``config/`` from (``('share/' + package_name + '/launch', glob('launch/*'))``), they already are.
The workspaces are the launch file's own (the folder holding its package) and the current folder
(``src/*``), as :mod:`shared_models.definitions.index` reads them.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from services.launch.errors import LaunchError
from shared_models.definitions.index import packages_in

__all__ = ["PackageNotFoundError", "Workspace", "find_launch_file_in_package"]

_LAUNCH_SUFFIXES = (".launch.py", "_launch.py", ".launch.xml", ".launch.yaml", ".launch.yml", ".py", ".xml", ".yaml")
_NOT_SEARCHED = {"build", "install", "log", "test", "__pycache__"}


class PackageNotFoundError(LaunchError, KeyError):
    """No package of that name in the launch's workspaces (ament_index_python's name for it)."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0])


class Workspace:
    """The folders packages are looked for in, and the packages found there (once)."""

    def __init__(self, roots: Iterable[Path]) -> None:
        self.roots: list[Path] = []
        for root in roots:
            root = root.resolve()
            if root not in self.roots:
                self.roots.append(root)
        self._packages: dict[str, Path] | None = None

    def packages(self) -> dict[str, Path]:
        """Every package found, by its package.xml name (the first root that has it wins)."""
        if self._packages is None:
            found: dict[str, Path] = {}
            for root in self.roots:
                for name, folder in packages_in(root).items():
                    found.setdefault(name, folder)
            self._packages = found
        return self._packages

    def share_directory(self, name: str) -> Path:
        """The package's share directory: its source folder (see the module docstring)."""
        folder = self.packages().get(name)
        if folder is None:
            where = ", ".join(str(root) for root in self.roots) or "no workspace"
            known = ", ".join(sorted(self.packages())) or "none"
            raise PackageNotFoundError(
                f"no package {name!r} in {where} (found: {known}); run from the workspace folder"
            )
        return folder


def find_launch_file_in_package(workspace: Workspace, package: str, name: str) -> Path:
    """``skydeck launch PKG FILE``: the file ``name`` in the package's ``launch/`` folder, else
    anywhere in the package (as ``ros2 launch`` finds it in the package's share directory)."""
    folder = workspace.share_directory(package)
    direct = folder / "launch" / name
    if direct.is_file():
        return direct
    found = sorted(path for path in _files(folder) if path.name == name)
    if found:
        return found[0]
    launch_files = sorted({path.name for path in _files(folder) if path.name.endswith(_LAUNCH_SUFFIXES[:5])})
    listed = ", ".join(launch_files) if launch_files else "none"
    raise LaunchError(f"package {package} ({folder}) has no launch file {name!r}; its launch files: {listed}")


def _files(folder: Path) -> list[Path]:
    files: list[Path] = []
    try:
        children = sorted(folder.iterdir())
    except OSError:
        return files
    for child in children:
        if child.name.startswith(".") or child.name in _NOT_SEARCHED:
            continue
        if child.is_dir():
            files += _files(child)
        elif child.is_file():
            files.append(child)
    return files
