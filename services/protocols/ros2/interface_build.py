"""ROS 2 interface packages for Skydeck's types that no wheel ships, built the ROS 2 way.

ROS 2's wheels bring std_msgs, geometry_msgs, sensor_msgs and the like, but not tf2_msgs, nor
Skydeck's own packages (ros_workshop, neato2_interfaces...), nor the subset of mavros_msgs that
the workshop uses. For each such package this writes its ``.msg``/``.srv`` files from Skydeck's
definitions (:mod:`shared_models.ros2msg`), a ``package.xml`` and a ``CMakeLists.txt`` calling
``rosidl_generate_interfaces``, and builds and installs it with cmake into the venv itself, laid
out as the wheels are (``lib/``, ``lib/python3.X/site-packages/``, ``share/``), so rclpy finds it
as it finds theirs. ``make install-ros2`` runs it once; it builds again only when Skydeck's
definitions change (a digest of them is kept beside the packages).

    python -m services.protocols.ros2.interface_build      # build what is missing or stale
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.util
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

from shared_models import Message, ServiceType, all_interfaces
from shared_models.catalogue import MESSAGE_PACKAGES
from shared_models.errors import SkydeckError
from shared_models.ros2msg import msg_file_text, specs_of, srv_file_text

__all__ = ["NOT_BRIDGED", "BuildFailed", "build_interfaces", "packages_to_build", "stamp_path"]

# The wheels' exported cmake targets name the include and site-packages folders of the machine
# that built them; they are pointed at this venv's before the interface build uses them.
_WHEEL_PYTHON_PREFIX = "/opt/python/cp311-cp311"
_CMAKE = """cmake_minimum_required(VERSION 3.16)
project({package})
find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)
{find_dependencies}
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
# The wheels were built with Python under {wheel_prefix}: their targets say so. Here it is
# this venv's Python. (rosidl's own find_package of service_msgs comes too late: found here.)
find_package(service_msgs REQUIRED)
get_property(_targets DIRECTORY PROPERTY IMPORTED_TARGETS)
foreach(_target ${{_targets}})
  get_target_property(_include ${{_target}} INTERFACE_INCLUDE_DIRECTORIES)
  if(_include)
    list(TRANSFORM _include REPLACE "^{wheel_prefix}/include/python3[.0-9]*$" "${{Python3_INCLUDE_DIRS}}")
    list(TRANSFORM _include REPLACE "^{wheel_prefix}/lib/python3[.0-9]*/site-packages" "{site_packages}")
    set_target_properties(${{_target}} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${{_include}}")
  endif()
endforeach()
rosidl_generate_interfaces(${{PROJECT_NAME}}
{files}
  DEPENDENCIES {dependencies})
ament_package()
"""
_PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>{package}</name>
  <version>0.0.0</version>
  <description>Skydeck's {package} types, generated from shared_models for the ROS 2 bridge</description>
  <maintainer email="skydeck@localhost.localdomain">Skydeck</maintainer>
  <license>MIT</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
{depends}
  <exec_depend>rosidl_default_runtime</exec_depend>
  <member_of_group>rosidl_interface_packages</member_of_group>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""


class BuildFailed(SkydeckError):
    """A package did not build; the message names it and where cmake's output is."""


def stamp_path(prefix: Path | None = None) -> Path:
    """Where the digest of the built definitions is kept."""
    return (prefix or Path(sys.prefix)) / "share" / "skydeck" / "ros2_interfaces.sha256"


# Skydeck's own plumbing, which no ROS 2 node speaks: rosapi's types (the rosbridge endpoint's)
# and the launch's kill_node. Not built (rosapi_msgs alone would take minutes); not bridged.
NOT_BRIDGED = frozenset({"rosapi_msgs", "skydeck_launch"})


def packages_to_build() -> list[str]:
    """Skydeck's message packages that no installed ROS 2 package provides, dependencies first."""
    return [
        package for package in MESSAGE_PACKAGES
        if package not in NOT_BRIDGED and _types_of(package) and not _has_wheel(package)
    ]


def _has_wheel(package: str) -> bool:
    spec = importlib.util.find_spec(package)
    if spec is None or spec.origin is None:
        return False
    # ours, built before, lives in the same site-packages: it is not a wheel
    return not (Path(spec.origin).parent / "_skydeck_generated").exists()


def _types_of(package: str) -> list[type[Message] | type[ServiceType]]:
    """The package's messages and services (a service's halves are its own; actions are not
    bridged)."""
    return [
        cls for name, cls in sorted(all_interfaces().items())
        if name.startswith(package + "/") and not name.endswith(("_Request", "_Response"))
        and isinstance(cls, type) and issubclass(cls, Message | ServiceType)
    ]


def _digest(packages: list[str]) -> str:
    text = []
    for package in packages:
        for cls in _types_of(package):
            body = srv_file_text(cls) if issubclass(cls, ServiceType) else msg_file_text(cls)
            text.append(f"{cls.__ros_type__}\n{body}")
    return hashlib.sha256("\n".join(text).encode()).hexdigest()


def _dependencies(package: str) -> list[str]:
    needed: set[str] = set()
    for cls in _types_of(package):
        parts = [cls.Request, cls.Response] if issubclass(cls, ServiceType) else [cls]
        for part in parts:
            needed |= {name.split("/", 1)[0] for name in specs_of(part)}
    needed.discard(package)
    # Skydeck's part types (std_srvs/srv/Trigger_Request) have no package of their own
    return sorted(needed)


def _write_package(package: str, root: Path, site_packages: str) -> None:
    files = []
    for cls in _types_of(package):
        kind, short = cls.__ros_type__.split("/")[1:]
        path = root / kind / f"{short}.{kind}"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(srv_file_text(cls) if issubclass(cls, ServiceType) else msg_file_text(cls))  # type: ignore[arg-type]
        files.append(f'  "{kind}/{short}.{kind}"')
    dependencies = _dependencies(package)
    (root / "CMakeLists.txt").write_text(_CMAKE.format(
        package=package,
        find_dependencies="\n".join(f"find_package({d} REQUIRED)" for d in dependencies),
        dependencies=" ".join(dependencies),
        files="\n".join(files),
        wheel_prefix=_WHEEL_PYTHON_PREFIX,
        site_packages=site_packages,
    ))
    (root / "package.xml").write_text(_PACKAGE_XML.format(
        package=package, depends="\n".join(f"  <depend>{d}</depend>" for d in dependencies)
    ))


def build_interfaces(*, force: bool = False, prefix: Path | None = None, log=print) -> list[str]:  # type: ignore[no-untyped-def]
    """Build and install every package :func:`packages_to_build` names; returns those built.

    Nothing is built when the digest of the definitions matches the last build's (``force``
    builds anyway). Raises :class:`BuildFailed` with cmake's last lines.
    """
    prefix = prefix or Path(sys.prefix)
    packages = packages_to_build()
    stamp = stamp_path(prefix)
    digest = _digest(packages)
    if not force and stamp.exists() and stamp.read_text().strip() == digest:
        return []
    for tool in ("cmake", "make"):
        if shutil.which(tool) is None:
            raise BuildFailed(f"building ROS 2's interfaces needs {tool}: `apt-get install cmake g++ make`")
    site_packages = sysconfig.get_paths(vars={"base": str(prefix), "platbase": str(prefix)})["purelib"]
    env = dict(os.environ)
    for variable in ("AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH"):
        env[variable] = os.pathsep.join(filter(None, [str(prefix), env.get(variable, "")]))
    with tempfile.TemporaryDirectory(prefix="skydeck-ros2-") as work:
        for package in packages:
            started = time.monotonic()
            source, build = Path(work) / "src" / package, Path(work) / "build" / package
            _write_package(package, source, site_packages)
            _run(package, [
                "cmake", "-S", str(source), "-B", str(build), f"-DCMAKE_INSTALL_PREFIX={prefix}",
                "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                "-DBUILD_TESTING=OFF", f"-DCMAKE_INSTALL_RPATH={prefix}/lib", "-DCMAKE_INSTALL_RPATH_USE_LINK_PATH=ON",
            ], env, build)
            _run(package, ["cmake", "--build", str(build), "-j", str(os.cpu_count() or 2)], env, build)
            _run(package, ["cmake", "--install", str(build)], env, build)
            marker = Path(site_packages) / package / "_skydeck_generated"
            marker.write_text("built by services.protocols.ros2.interface_build from shared_models\n")
            log(f"built ROS 2 interfaces {package} in {time.monotonic() - started:.0f} s")
    stamp.parent.mkdir(parents=True, exist_ok=True)
    stamp.write_text(digest + "\n")
    return packages


def _run(package: str, command: list[str], env: dict[str, str], build: Path) -> None:
    build.mkdir(parents=True, exist_ok=True)
    log_file = build / "build.log"
    with log_file.open("a") as out:
        result = subprocess.run(command, env=env, stdout=out, stderr=subprocess.STDOUT, check=False)
    if result.returncode != 0:
        tail = "\n".join(log_file.read_text().splitlines()[-15:])
        raise BuildFailed(f"building ROS 2 interfaces {package} failed ({' '.join(command[:2])}):\n{tail}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--force", action="store_true", help="build even if the definitions did not change")
    args = parser.parse_args(argv)
    try:
        built = build_interfaces(force=args.force)
    except BuildFailed as error:
        print(f"skydeck: error: {error}", file=sys.stderr)
        return 1
    print(f"ROS 2 interfaces built: {', '.join(built)}" if built else "ROS 2 interfaces up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
