"""What ``skydeck run`` runs from a workspace: a package's executable, or a file in a package.

    skydeck run my_pkg turtle_circle          ros2 run: the console script of an ament_python
                                              package (setup.py / setup.cfg entry points)
    skydeck run my_pkg circle.py              rosrun: a catkin package's script (src/, scripts/...)
    skydeck run src/my_pkg/my_pkg/circle.py   a file inside a Python package: run as
                                              ``my_pkg.circle``, so ``from .helpers import x`` works

Packages are found where :mod:`shared_models.definitions.index` finds them: the workspaces this
process was given (``--workspace DIR``, the running file's, the current folder). The same index
serves their ``msg``/``srv``/``action`` files, so a node's own message package is found beside it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from services.ros.errors import RosFacadeError
from services.ros.setup_files import console_scripts
from shared_models.definitions.index import InterfacePackage, index

__all__ = ["PackageTargetError", "Target", "file_target", "package_target", "workspace_of"]


class PackageTargetError(RosFacadeError, LookupError):
    """No such package in the workspace, or no such executable in the package."""


@dataclass(frozen=True)
class Target:
    """A program to run: a module of a Python package (with the entry point's ``function``, or
    as ``__main__``), or a plain file; ``import_root`` goes first on ``sys.path``. ``file`` is
    the program's file when it was given as one (its folder is on ``sys.path`` too, as
    ``python3 FILE`` puts it)."""

    argv0: str
    import_root: Path
    module: str | None = None
    function: str | None = None
    file: Path | None = None


def workspace_of(path: Path) -> Path | None:
    """The folder of packages a file's package sits in (for its siblings' interfaces)."""
    for folder in path.resolve().parents:
        if (folder / "package.xml").is_file():
            return folder.parent
    return None


def file_target(path: Path) -> Target:
    """``path`` as a module of its Python package (folders with ``__init__.py`` above it), or as
    a plain file when it is in none."""
    path = path.resolve()
    parts = [path.stem]
    folder = path.parent
    while (folder / "__init__.py").is_file():
        parts.insert(0, folder.name)
        folder = folder.parent
    if len(parts) == 1:
        return Target(str(path), path.parent, file=path)
    return Target(str(path), folder, module=".".join(parts), file=path)


def package_target(package_name: str, executable: str) -> Target:
    """What ``skydeck run PACKAGE EXECUTABLE`` runs (see the module docstring)."""
    package = _package(package_name)
    scripts = console_scripts(package.folder)
    entry = scripts.get(executable)
    if entry is not None:
        root = _import_root(package, entry.module)
        return Target(executable, root, module=entry.module, function=entry.function)
    if scripts and not executable.endswith(".py"):
        raise PackageTargetError(
            f"package {package.name} has no executable {executable!r}; its entry points: {', '.join(sorted(scripts))}"
        )
    from services.launch.ros_packages import PackageNotFound, RosPackage

    try:
        program = RosPackage(package.name, package.folder).program(executable)
    except PackageNotFound as error:
        where = f"; its entry points: {', '.join(sorted(scripts))}" if scripts else " (it has no console_scripts)"
        raise PackageTargetError(f"{error}{where}") from None
    target = file_target(program)
    return Target(str(program), target.import_root, module=target.module, file=target.file)


def _package(name: str) -> InterfacePackage:
    package = index.find(name)
    if package is not None and not package.shipped:
        return package
    found = sorted(p.name for p in index.packages().values() if not p.shipped)
    if package is not None:
        raise PackageTargetError(f"{name} is a package of interfaces Skydeck ships: it has no programs to run")
    where = ", ".join(str(w) for w in index.workspaces) or "no workspace"
    known = f"found: {', '.join(found)}" if found else "found none"
    raise PackageTargetError(
        f"no package {name} in {where} ({known}); run from the workspace folder or give --workspace DIR"
    )


def _import_root(package: InterfacePackage, module: str) -> Path:
    """The folder ``module`` imports from: the package's folder (ament_python's layout) or its src/."""
    top = module.split(".", 1)[0]
    for root in (package.folder, package.folder / "src"):
        if (root / top).is_dir() or (root / f"{top}.py").is_file():
            return root
    raise PackageTargetError(
        f"package {package.name}: its entry point names the module {module}, but {package.folder} has no {top}/"
    )
