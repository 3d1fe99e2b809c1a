"""ROS 2 launch files (Python, XML, YAML) read and evaluated: what each action becomes for the
supervisor, which kind a file is, and every error as one line naming the file and line."""

from __future__ import annotations

import sys
import types
from pathlib import Path

import pytest

from services.launch import LaunchFileError, launch_arguments, package_launch_file
from services.launch.errors import LaunchError
from services.launch.plan import NodePlan, default_command
from services.launch.ros2 import load_ros2_launch, ros2_kind
from services.launch.ros2.model import Ros2Launch
from tests.services.launch.ros2_workspace import write_launch_workspace

pytestmark = [pytest.mark.timeout(30)]

FORMATS = ("pair.launch.py", "pair.launch.xml", "pair.launch.yaml")


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    return write_launch_workspace(tmp_path / "ws")


@pytest.fixture
def package(workspace: Path) -> Path:
    return workspace / "src" / "launch_demo"


def _load(path: Path, environ: dict[str, str] | None = None, **args: str) -> Ros2Launch:
    return load_ros2_launch(path, args, environ=environ or {}, cwd=path.parent)


def _write(package: Path, name: str, text: str) -> Path:
    path = package / "launch" / name
    path.write_text(text)
    return path


def _fails(package: Path, name: str, text: str, **args: str) -> str:
    with pytest.raises(LaunchFileError) as caught:
        _load(_write(package, name, text), **args)
    message = str(caught.value)
    assert "\n" not in message
    return message


_PY_HEAD = (
    "from launch import LaunchDescription\n"
    "from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription, SetLaunchConfiguration\n"
    "from launch.conditions import IfCondition, UnlessCondition\n"
    "from launch.substitutions import EnvironmentVariable, LaunchConfiguration, TextSubstitution\n"
    "from launch_ros.actions import Node, PushROSNamespace\n"
    "\n"
    "def generate_launch_description():\n"
)


@pytest.mark.parametrize("name", FORMATS)
def test_the_three_formats_make_the_same_launch(package: Path, name: str) -> None:
    launch = _load(package / "launch" / name, greeting="hey")
    spec = launch.spec(start_core=True)
    assert [(n.name, n.package, n.run, n.port_offset) for n in spec.nodes] == [
        ("core", None, "core", 0),
        ("robot1/speaker", "launch_demo", "talker", 2),
        ("robot1/ear", "launch_demo", "listener", 3),
    ]
    params = str(package / "config" / "talker.yaml")
    speaker, ear = spec.nodes[1].args, spec.nodes[2].args
    ros = list(speaker[speaker.index("--ros-args") + 1 :])
    assert ros == ["-r", "__node:=speaker", "-r", "__ns:=/robot1", "--params-file", params, "-p", "greeting:=hey", "-r", "chatter:=news"]
    assert list(ear[ear.index("--ros-args") + 1 :]) == ["-r", "__node:=ear", "-r", "__ns:=/robot1", "-r", "chatter:=news"]
    assert speaker[:2] == ("--workspace", str(package.parent))
    assert list(launch.arguments) == ["greeting", "robot", "topic"]
    assert launch.arguments["greeting"].description == "what the talker says"
    assert not spec.nodes[1].respawn  # ROS 2's default


def test_a_package_node_runs_as_skydeck_run_package_executable(package: Path) -> None:
    node = _load(package / "launch" / "pair.launch.py").spec(start_core=False).nodes[0]
    plan = NodePlan(name=node.name, run=node.run, port=9002, package=node.package, args=node.args)
    command = default_command(plan)
    assert command[3:8] == ["run", "launch_demo", "talker", "--port", "9002"]


def test_skydeck_launch_package_file_finds_it_in_the_workspace(workspace: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(workspace)
    assert package_launch_file("launch_demo", "pair.launch.xml") == workspace / "src/launch_demo/launch/pair.launch.xml"
    with pytest.raises(LaunchError, match=r"has no launch file 'nope.launch.py'; its launch files: listener.launch.py, pair"):
        package_launch_file("launch_demo", "nope.launch.py")
    with pytest.raises(LaunchError, match=r"no package 'other' in .* \(found: launch_demo\)"):
        package_launch_file("other", "pair.launch.py")


def test_show_args_lists_the_includes_arguments_too(package: Path) -> None:
    for name in FORMATS:
        assert list(launch_arguments(package / "launch" / name)) == ["greeting", "robot", "topic"]


def test_parameters_keep_their_types_and_nest(package: Path) -> None:
    path = _write(package, "params.launch.py", _PY_HEAD + (
        "    return LaunchDescription([Node(package='launch_demo', executable='talker', parameters=[\n"
        "        {'rate': 5.0, 'count': 3, 'on': True, 'label': '1', 'ids': [1, 2], 'gains': {'p': 0.5},\n"
        "         'where': LaunchConfiguration('w', default='home')}])])\n"
    ))  # fmt: skip
    args = _load(path).nodes[0].ros_arguments
    assert args == (
        "-p", "rate:=5.0", "-p", "count:=3", "-p", "on:=true", "-p", "label:='1'", "-p", "ids:=[1, 2]",
        "-p", "gains.p:=0.5", "-p", "where:=home",
    )  # fmt: skip


def test_conditions_let_groups_and_namespaces(package: Path) -> None:
    path = _write(package, "cond.launch.py", _PY_HEAD + (
        "    return LaunchDescription([\n"
        "        DeclareLaunchArgument('sim', default_value='true', choices=['true', 'false']),\n"
        "        SetLaunchConfiguration('ns', 'team'),\n"
        "        Node(package='launch_demo', executable='talker', name='a', condition=IfCondition(LaunchConfiguration('sim'))),\n"
        "        Node(package='launch_demo', executable='talker', name='b', condition=UnlessCondition(LaunchConfiguration('sim'))),\n"
        "        GroupAction([PushROSNamespace(LaunchConfiguration('ns')), Node(package='launch_demo', executable='listener',\n"
        "            namespace='left', arguments=['--x', EnvironmentVariable('HOME_X', default_value='none')])]),\n"
        "        GroupAction([PushROSNamespace('outer'), Node(package='launch_demo', executable='listener', namespace='/abs')]),\n"
        "        Node(package='skydeck', executable='teleop', name=[TextSubstitution(text='tele'), 'op']),\n"
        "    ])\n"
    ))  # fmt: skip
    launch = _load(path)
    assert [(n.graph_name, n.namespace) for n in launch.nodes] == [
        ("a", ""), ("team/left/listener", "/team/left"), ("abs/listener", "/abs"), ("teleop", ""),
    ]  # fmt: skip
    assert launch.nodes[1].arguments == ("--x", "none")
    assert [n.name for n in _load(path, sim="false").nodes][:1] == ["b"]
    teleop = launch.spec(start_core=False).nodes[-1]
    assert (teleop.run, teleop.package) == ("teleop", None)  # a built-in, run by name
    assert "--workspace" not in teleop.args
    with pytest.raises(LaunchFileError, match=r"cond.launch.py:9: the launch argument sim:=maybe is not one of its choices"):
        _load(path, sim="maybe")


def test_unnamed_nodes_of_one_executable_get_distinct_launch_names(package: Path) -> None:
    path = _write(package, "two.launch.xml", '<launch><node pkg="launch_demo" exec="talker"/><node pkg="launch_demo" exec="talker"/></launch>')
    assert [n.name for n in _load(path).spec(start_core=False).nodes] == ["talker", "talker-2"]


def test_xml_and_yaml_if_unless_let_and_env(package: Path) -> None:
    xml = _write(package, "c.launch.xml", (
        '<launch>\n  <arg name="fast" default="false"/>\n  <let name="who" value="$(env WHO nobody)"/>\n'
        '  <node pkg="launch_demo" exec="talker" name="$(var who)" if="$(var fast)"/>\n'
        '  <node pkg="launch_demo" exec="listener" args="--a $(var who)" unless="$(var fast)">\n'
        '    <env name="LEVEL" value="2"/>\n  </node>\n</launch>\n'
    ))  # fmt: skip
    slow = _load(xml)
    assert [(n.executable, n.arguments, n.env) for n in slow.nodes] == [("listener", ("--a", "nobody"), (("LEVEL", "2"),))]
    assert [n.name for n in _load(xml, {"WHO": "ann"}, fast="true").nodes] == ["ann"]
    yaml_file = _write(package, "c.launch.yaml", (
        "launch:\n- arg: {name: fast, default: 'true'}\n- group:\n    scoped: false\n    children:\n"
        "    - node: {pkg: launch_demo, exec: talker, if: $(var fast), param: [{name: ids, value: [1, 2]}]}\n"
    ))  # fmt: skip
    assert _load(yaml_file).nodes[0].ros_arguments == ("-p", "ids:=[1, 2]")


@pytest.mark.parametrize(
    ("name", "text", "match"),
    [
        ("a.launch.py", "from launch.actions import ExecuteProcess\n", r"a.launch.py:1: launch.actions.ExecuteProcess is not provided by Skydeck"),
        ("b.launch.py", "import os\nimport launch.event_handlers\n", r"b.launch.py:2: the module launch.event_handlers is not provided by Skydeck"),
        ("c.launch.py", _PY_HEAD + "    return LaunchDescription([Node(package='launch_demo', executable='talker',\n        prefix='gdb')])\n",
         r"c.launch.py:8: launch_ros.actions.Node\(prefix=...\) is not provided by Skydeck"),
        ("d.launch.py", "def generate_launch_description():\n    return nothing\n", r"d.launch.py:2: NameError: name 'nothing' is not defined"),
        ("e.launch.py", "x = 1\n", r"e.launch.py: defines no generate_launch_description\(\)"),
        ("f.launch.py", "def generate_launch_description(:\n", r"f.launch.py:1: SyntaxError"),
        ("g.launch.py", "import launch\ndef generate_launch_description():\n    return launch.LaunchDescription([launch.actions.TimerAction(period=1, actions=[])])\n",
         r"g.launch.py:3: launch.actions.TimerAction is not provided by Skydeck"),
        ("h.launch.py", _PY_HEAD + "    return LaunchDescription([Node(package='launch_demo', executable='talkr')])\n",
         r"h.launch.py:8: package launch_demo has no executable 'talkr'; its entry points: listener, talker"),
        ("i.launch.py", _PY_HEAD + "    return LaunchDescription([Node(package='nopkg', executable='x')])\n", r"i.launch.py:8: no package 'nopkg'"),
        ("j.launch.py", _PY_HEAD + "    return LaunchDescription([DeclareLaunchArgument('need')])\n",
         r"j.launch.py:8: the launch argument 'need' has no default: pass need:=VALUE"),
        ("k.launch.py", _PY_HEAD + "    return LaunchDescription([IncludeLaunchDescription('missing.launch.py')])\n",
         r"k.launch.py:8: the included launch file missing.launch.py does not exist"),
        ("l.launch.py", _PY_HEAD + "    return LaunchDescription([Node(package='launch_demo', executable='talker', parameters=['no.yaml'])])\n",
         r"l.launch.py:8: the parameters file no.yaml does not exist"),
        ("m.launch.py", "def generate_launch_description():\n    return [1]\n", r"returned list, not a LaunchDescription"),
        ("n.launch.py", _PY_HEAD + "    return LaunchDescription([Node(package='skydeck', executable='nope')])\n", r"Skydeck has no built-in node 'nope'"),
        ("a.launch.xml", '<launch>\n<node pkg="launch_demo" exec="talker" launch-prefix="gdb"/>\n</launch>', r"a.launch.xml:2: <node launch-prefix=...> is not provided by Skydeck"),
        ("b.launch.xml", '<launch>\n<executable cmd="ls"/>\n</launch>', r"b.launch.xml:2: <executable> is not provided by Skydeck"),
        ("c.launch.xml", '<launch>\n<node pkg="launch_demo" exec="$(eval 1)"/>\n</launch>', r"c.launch.xml:2: \$\(eval 1\) is not provided by Skydeck"),
        ("d.launch.xml", '<launch>\n<node pkg="launch_demo" name="x"/>\n</launch>', r"d.launch.xml:2: <node> needs the attribute 'exec'"),
        ("e.launch.xml", '<launch>\n<node pkg="launch_demo" exec="talker" name="$(var who)"/>\n</launch>',
         r"e.launch.xml:2: launch configuration 'who' is not set"),
        ("a.launch.yaml", "launch:\n- node: {pkg: launch_demo, exec: talker}\n- timer: {period: 1}\n", r"a.launch.yaml:3: <timer> is not provided by Skydeck"),
        ("b.launch.yaml", "launch:\n- node: [1, 2\n", r"b.launch.yaml:\d+: YAML syntax error"),
        ("c.launch.yaml", "launch: 5\n", r"c.launch.yaml:1: `launch:` is a list of actions"),
    ],
)
def test_errors_are_one_line_with_file_and_line(package: Path, name: str, text: str, match: str) -> None:
    assert pytest.raises(LaunchFileError, _load, _write(package, name, text)).match(match)


def test_an_undeclared_command_line_argument_is_refused(package: Path) -> None:
    with pytest.raises(LaunchFileError, match=r"nothing:=1: the launch declares no argument 'nothing' \(it declares: greeting, robot, topic\)"):
        _load(package / "launch" / "pair.launch.py", nothing="1")


def test_kinds_by_name_and_content(tmp_path: Path) -> None:
    files = {
        "a.launch.py": "",
        "ros1.launch": '<launch><node pkg="p" type="t.py" name="n"/></launch>',
        "ros1.xml": '<launch><arg name="x" default="$(find p)"/></launch>',
        "ros2.launch": '<launch><node pkg="p" exec="t"/></launch>',
        "ros2.launch.xml": '<launch><arg name="x" default="1"/></launch>',
        "plain.xml": '<launch><arg name="x" default="1"/></launch>',
        "ros2.yaml": "launch:\n- arg: {name: x}\n",
        "skydeck.yaml": "nodes:\n- {name: core, run: core, port_offset: 0}\n",
    }
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    kinds = {name: ros2_kind(tmp_path / name) for name in files}
    assert kinds == {
        "a.launch.py": "python", "ros1.launch": None, "ros1.xml": None, "ros2.launch": "xml",
        "ros2.launch.xml": "xml", "plain.xml": None, "ros2.yaml": "yaml", "skydeck.yaml": None,
    }  # fmt: skip


def test_ours_win_over_a_real_launch_package_and_it_is_put_back(package: Path) -> None:
    real = types.ModuleType("launch")
    real_actions = types.ModuleType("launch.actions")
    saved = {name: sys.modules.get(name) for name in ("launch", "launch.actions")}
    sys.modules.update({"launch": real, "launch.actions": real_actions})
    try:
        launch = _load(package / "launch" / "pair.launch.py")
        assert len(launch.nodes) == 2
        assert sys.modules["launch"] is real and sys.modules["launch.actions"] is real_actions
        assert "launch_ros" not in sys.modules
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module


def test_skydecks_own_yaml_names_a_package_executable_too(tmp_path: Path) -> None:
    from services.launch import load_launch_file

    path = tmp_path / "mine.yaml"
    path.write_text("nodes:\n  - {name: talker, package: launch_demo, run: talker, port_offset: 2}\n")
    node = load_launch_file(path, {}).nodes[0]
    assert (node.package, node.run) == ("launch_demo", "talker")  # not taken as a path
    path.write_text("nodes:\n  - {name: talker, run: talker, port_offset: 2}\n")
    with pytest.raises(LaunchFileError, match=r"nodes\[0\].run: 'talker' is neither a built-in"):
        load_launch_file(path, {})
