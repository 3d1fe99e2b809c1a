"""ROS 1 packages on disk, as a roslaunch file names them: ``pkg="ros_workshop"``,
``$(find ros_workshop)``.

A package is a folder holding ``package.xml``; its name is the file's ``<name>``. A launch file
belongs to the package whose folder holds it (the nearest ``package.xml`` above it); other
packages are found beside that one, in the same workspace folder (``catkin_ws/src/*``), as
``rospack`` would find them in a sourced workspace. A node's ``type`` is a file of its package,
looked for where catkin packages keep their programs: ``src/``, ``scripts/``, ``nodes/``,
``bin/``, the package folder itself, and its Python module folders (``src/PKG/``, ``PKG/``:
folders holding ``__init__.py``).
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from pathlib import Path

from shared_models.errors import SkydeckError

__all__ = ["PackageNotFound", "RosPackage", "find_package", "package_of"]

_PROGRAM_FOLDERS = ("src", "scripts", "nodes", "bin", ".")
_WORKSPACE_DEPTH = 2  # catkin_ws/src/PKG and catkin_ws/src/GROUP/PKG


class PackageNotFound(SkydeckError, LookupError):
    """No package of that name, or no such program in the package; the message says where we looked."""


@dataclass(frozen=True)
class RosPackage:
    """One package: its name (from package.xml) and its folder."""

    name: str
    folder: Path

    @classmethod
    def read(cls, folder: Path) -> RosPackage:
        """The package whose ``package.xml`` is in ``folder`` (named by the folder if it has no ``<name>``)."""
        try:
            root = ElementTree.parse(folder / "package.xml").getroot()
            name = (root.findtext("name") or "").strip()
        except (OSError, ElementTree.ParseError):
            name = ""
        return cls(name or folder.name, folder)

    def program(self, node_type: str) -> Path:
        """The file ``node_type`` names in this package (see the module docstring)."""
        for folder in self._program_folders():
            candidate = folder / node_type
            if candidate.is_file():
                return candidate.resolve()
        searched = ", ".join(str(f.relative_to(self.folder)) or "." for f in self._program_folders())
        raise PackageNotFound(f"package {self.name} has no {node_type} (looked in {searched} of {self.folder})")

    def _program_folders(self) -> list[Path]:
        folders = [(self.folder / name) for name in _PROGRAM_FOLDERS if (self.folder / name).is_dir()]
        for parent in (self.folder, self.folder / "src"):
            if parent.is_dir():
                folders += sorted(p for p in parent.iterdir() if p.is_dir() and (p / "__init__.py").is_file())
        return folders


def package_of(path: Path) -> RosPackage | None:
    """The package a file belongs to: the nearest folder above it holding package.xml."""
    for folder in path.resolve().parents:
        if (folder / "package.xml").is_file():
            return RosPackage.read(folder)
    return None


def find_package(name: str, near: RosPackage | None) -> RosPackage:
    """The package ``name``: ``near`` itself, or one beside it in its workspace folder."""
    if near is None:
        raise PackageNotFound(
            f"no package {name}: the launch file is in no package (no package.xml in a folder above it)"
        )
    if near.name == name:
        return near
    workspace = near.folder.parent
    for package_xml in sorted(_package_files(workspace, _WORKSPACE_DEPTH)):
        package = RosPackage.read(package_xml.parent)
        if package.name == name:
            return package
    raise PackageNotFound(f"no package {name} in {workspace} (the folder that holds {near.name})")


def _package_files(folder: Path, depth: int) -> list[Path]:
    found: list[Path] = []
    try:
        children = [child for child in folder.iterdir() if child.is_dir() and not child.name.startswith(".")]
    except OSError:
        return found
    for child in children:
        if (child / "package.xml").is_file():
            found.append(child / "package.xml")
        elif depth > 1:
            found += _package_files(child, depth - 1)
    return found
