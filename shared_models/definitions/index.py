"""Where ROS packages are on disk: the interface packages Skydeck ships, and a workspace's.

A package is a folder holding ``package.xml`` (its name is the file's ``<name>``). Skydeck ships
the tutorials' interface packages as such folders, ``shared_models/packages/*`` (read by the same
loader as a student's own). A workspace is found the way ``colcon`` and ``catkin`` lay one out::

    ros2_ws/                 a workspace folder: its src/PKG and src/GROUP/PKG
    ros2_ws/src/             a folder of packages: PKG and GROUP/PKG
    my_packages/             any other folder without src/: its PKG
    ros2_ws/src/my_pkg/      a package itself

Build output (``build``, ``install``, ``log``, ``devel``) and hidden folders are never entered,
nor is a package's own folder (packages do not nest). The process's index holds the shipped
packages and the workspaces it was given (:func:`use_workspace`); a shipped package wins over a
workspace's of the same name, as Skydeck's own types always do.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from shared_models.definitions.parser import KINDS

__all__ = ["SHIPPED_FOLDER", "InterfacePackage", "PackageIndex", "index", "packages_in", "use_workspace"]

SHIPPED_FOLDER = Path(__file__).resolve().parent.parent / "packages"
_SKIPPED = frozenset({"build", "install", "log", "devel", "node_modules", "__pycache__", "site-packages"})
_DEPTH = 2  # PKG and GROUP/PKG below a folder of packages


@dataclass(frozen=True)
class InterfacePackage:
    """One package on disk: its name, folder, and whether Skydeck ships it."""

    name: str
    folder: Path
    shipped: bool = False

    @cached_property
    def files(self) -> dict[str, Path]:
        """Its definition files by the type each declares (``my_pkg/msg/Status``)."""
        found: dict[str, Path] = {}
        for kind in KINDS:
            folder = self.folder / kind
            if folder.is_dir():
                for path in sorted(folder.glob(f"*.{kind}")):
                    found[f"{self.name}/{kind}/{path.stem}"] = path
        return found

    @property
    def has_interfaces(self) -> bool:
        return bool(self.files)


def package_name(folder: Path) -> str:
    """The ``<name>`` of ``folder/package.xml`` (the folder's name if it has none)."""
    try:
        name = (ElementTree.parse(folder / "package.xml").getroot().findtext("name") or "").strip()
    except (OSError, ElementTree.ParseError):
        name = ""
    return name or folder.name


def packages_in(root: Path) -> dict[str, Path]:
    """The package folders of a workspace folder, a folder of packages, or a package (by name)."""
    root = root.resolve()
    if (root / "package.xml").is_file():
        return {package_name(root): root}
    if (root / "src").is_dir():
        folder, depth = root / "src", _DEPTH
    else:  # a folder of packages: src/ itself looks two deep, any other folder one (never a home's tree)
        folder, depth = root, _DEPTH if root.name == "src" else 1
    found: dict[str, Path] = {}
    for package in _package_folders(folder, depth):
        found.setdefault(package_name(package), package)
    return found


def _package_folders(folder: Path, depth: int) -> list[Path]:
    try:
        children = sorted(
            child for child in folder.iterdir()
            if child.is_dir() and not child.name.startswith(".") and child.name not in _SKIPPED
        )  # fmt: skip
    except OSError:
        return []
    found: list[Path] = []
    for child in children:
        if (child / "package.xml").is_file():
            found.append(child)
        elif depth > 1:
            found += _package_folders(child, depth - 1)
    return found


class PackageIndex:
    """The packages one process knows: Skydeck's shipped ones, then its workspaces'."""

    def __init__(self) -> None:
        self._workspaces: list[Path] = []
        self._packages: dict[str, InterfacePackage] | None = None

    def use_workspace(self, folder: Path) -> None:
        """Know the packages of ``folder`` too (a workspace, a folder of packages, a package)."""
        folder = folder.resolve()
        if folder not in self._workspaces:
            self._workspaces.append(folder)
            self._packages = None

    @property
    def workspaces(self) -> list[Path]:
        return list(self._workspaces)

    def packages(self) -> dict[str, InterfacePackage]:
        """Every package known, by name (found once, then kept)."""
        if self._packages is None:
            packages = {
                name: InterfacePackage(name, folder, shipped=True)
                for name, folder in packages_in(SHIPPED_FOLDER).items()
            }
            for workspace in self._workspaces:
                for name, folder in packages_in(workspace).items():
                    packages.setdefault(name, InterfacePackage(name, folder))
            self._packages = packages
        return self._packages

    def find(self, name: str) -> InterfacePackage | None:
        return self.packages().get(name)

    def interface_packages(self, *, shipped: bool | None = None) -> list[InterfacePackage]:
        """The packages that declare types (all, or only the shipped or only the workspaces')."""
        return [
            package for package in self.packages().values()
            if package.has_interfaces and (shipped is None or package.shipped == shipped)
        ]  # fmt: skip


index = PackageIndex()
"""The process's index (one per process, as a sourced workspace is)."""


def use_workspace(folder: Path) -> None:
    """Know the packages of ``folder`` in this process (``skydeck run``'s ``--workspace``)."""
    index.use_workspace(folder)
