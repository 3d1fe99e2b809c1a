"""What ``skydeck run`` finds in a workspace: console scripts read from setup.py (never run) and
setup.cfg, catkin scripts by file name, files inside Python packages run as their modules."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.ros.setup_files import SetupFileError, console_scripts
from services.ros.workspace import PackageTargetError, file_target, package_target
from shared_models.definitions.index import PackageIndex, packages_in


def write(root: Path, files: dict[str, str]) -> Path:
    for relative, text in files.items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


def package_xml(name: str) -> str:
    return f"<package format='3'><name>{name}</name><version>0.0.0</version></package>"


def scripts(folder: Path) -> dict[str, str]:
    return {name: f"{point.module}:{point.function}" for name, point in console_scripts(folder).items()}


def test_setup_py_is_read_without_running_it(tmp_path: Path) -> None:
    write(tmp_path, {"setup.py": """
import os
from glob import glob
from setuptools import setup
raise SystemExit("never run")
package_name = 'turtle_tools'
module = package_name + '.circle'
setup(
    name=package_name,
    data_files=[(os.path.join('share', package_name), glob('launch/*.py'))],
    entry_points={
        'console_scripts': [
            'circle = ' + module + ':main',
            f'square = {package_name}.square:run',
            'teleop=turtle_tools.teleop:main [keyboard]',
        ],
    },
)
"""})
    assert scripts(tmp_path) == {
        "circle": "turtle_tools.circle:main", "square": "turtle_tools.square:run", "teleop": "turtle_tools.teleop:main",
    }  # fmt: skip


def test_setup_cfg_and_setup_py_with_no_entry_points(tmp_path: Path) -> None:
    write(tmp_path, {
        "setup.cfg": "[options.entry_points]\nconsole_scripts =\n    talker = demo.talker:main\n    listener = demo.listener:main\n",
        "setup.py": "from setuptools import setup\nsetup()\n",
    })  # fmt: skip
    assert scripts(tmp_path) == {"talker": "demo.talker:main", "listener": "demo.listener:main"}


@pytest.mark.parametrize(
    ("setup", "problem"),
    [
        ("setup(entry_points={'console_scripts': [make_name()]})", "must be written with literals"),
        ("setup(entry_points={'console_scripts': ['talker']})", "'talker' is not a console script"),
        ("setup(entry_points=[1])", "entry_points is not a dict of lists"),
        ("setup(\n", "cannot read it as Python"),
    ],
)
def test_an_unreadable_setup_py_is_one_line(tmp_path: Path, setup: str, problem: str) -> None:
    write(tmp_path, {"setup.py": "from setuptools import setup\n" + setup})
    with pytest.raises(SetupFileError, match=problem) as raised:
        console_scripts(tmp_path)
    assert "\n" not in str(raised.value)


def test_a_file_in_a_python_package_runs_as_its_module(tmp_path: Path) -> None:
    write(tmp_path, {"pkg/pkg/__init__.py": "", "pkg/pkg/sub/__init__.py": "", "pkg/pkg/sub/node.py": "", "loose/node.py": ""})
    target = file_target(tmp_path / "pkg/pkg/sub/node.py")
    assert (target.module, target.import_root, target.function) == ("pkg.sub.node", tmp_path / "pkg", None)
    loose = file_target(tmp_path / "loose/node.py")
    assert loose.module is None and loose.file == tmp_path / "loose/node.py"


@pytest.fixture
def workspace(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    write(tmp_path, {
        "src/ament_pkg/package.xml": package_xml("ament_pkg"),
        "src/ament_pkg/setup.py": "from setuptools import setup\nsetup(entry_points={'console_scripts': ['go = ament_pkg.go:main']})\n",
        "src/ament_pkg/ament_pkg/__init__.py": "",
        "src/ament_pkg/ament_pkg/go.py": "",
        "src/group/catkin_pkg/package.xml": package_xml("catkin_pkg"),
        "src/group/catkin_pkg/scripts/talker.py": "",
        "src/group/catkin_pkg/msg/Num.msg": "int64 num\n",
        "build/ignored/package.xml": package_xml("ignored"),
    })  # fmt: skip
    packages = PackageIndex()  # this test's, not the process's
    packages.use_workspace(tmp_path)
    monkeypatch.setattr("services.ros.workspace.index", packages)
    return tmp_path


def test_ros2_and_ros1_targets(workspace: Path) -> None:
    go = package_target("ament_pkg", "go")
    assert (go.module, go.function, go.import_root) == ("ament_pkg.go", "main", workspace / "src/ament_pkg")
    talker = package_target("catkin_pkg", "talker.py")
    assert talker.file == workspace / "src/group/catkin_pkg/scripts/talker.py" and talker.module is None
    assert set(packages_in(workspace)) == {"ament_pkg", "catkin_pkg"}  # build/ is never read


def test_unknown_packages_and_executables_say_what_there_is(workspace: Path) -> None:
    with pytest.raises(PackageTargetError, match=r"no package nope in .*\(found: ament_pkg, catkin_pkg\)"):
        package_target("nope", "go")
    with pytest.raises(PackageTargetError, match=r"^package ament_pkg has no executable 'stop'; its entry points: go$"):
        package_target("ament_pkg", "stop")
    with pytest.raises(PackageTargetError, match=r"package catkin_pkg has no listener.py .*\(it has no console_scripts\)"):
        package_target("catkin_pkg", "listener.py")
    with pytest.raises(PackageTargetError, match="turtlesim is a package of interfaces Skydeck ships"):
        package_target("turtlesim", "turtlesim_node")


def test_a_shipped_package_wins_over_a_workspace_one(tmp_path: Path) -> None:
    write(tmp_path, {"turtlesim/package.xml": package_xml("turtlesim"), "turtlesim/msg/Pose.msg": "int8 x\n"})
    packages = PackageIndex()
    packages.use_workspace(tmp_path)
    assert packages.find("turtlesim").shipped  # type: ignore[union-attr]
