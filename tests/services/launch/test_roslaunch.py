"""roslaunch XML files: each tag, substitution and error, read from files in a catkin-style
workspace built in tmp_path; and what they become for the supervisor."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.launch import (
    LaunchFileError,
    RosLaunch,
    core_answers,
    load_roslaunch_file,
)
from services.launch.roslaunch import NODE_PORT_OFFSET

pytestmark = [pytest.mark.timeout(30)]


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """catkin_ws/src with two packages: `demo` (nodes in src/, scripts/, nodes/, a module folder)
    and `other` beside it."""
    src = tmp_path / "catkin_ws" / "src"
    demo = src / "demo"
    for folder, name in (("src", "talker.py"), ("scripts", "listener.py"), ("nodes", "relay.py"), ("src/demo", "tool.py")):
        (demo / folder).mkdir(parents=True, exist_ok=True)
        (demo / folder / name).write_text("import rospy\n")
    (demo / "src" / "demo" / "__init__.py").write_text("")
    (demo / "src" / "binary").write_text("ELF")
    (demo / "package.xml").write_text('<?xml version="1.0"?>\n<package format="2"><name>demo</name></package>\n')
    (demo / "launch").mkdir()
    other = src / "other_pkg_folder"
    (other / "scripts").mkdir(parents=True)
    (other / "scripts" / "helper.py").write_text("import rospy\n")
    (other / "package.xml").write_text("<package><name>other</name></package>")
    return demo


def _launch(workspace: Path, body: str, name: str = "test.launch", **args: str) -> RosLaunch:
    path = workspace / "launch" / name
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return load_roslaunch_file(path, args)


def _fails(workspace: Path, body: str, match: str, **args: str) -> LaunchFileError:
    with pytest.raises(LaunchFileError, match=match) as caught:
        _launch(workspace, body, **args)
    return caught.value


def _parameters(launch: RosLaunch) -> dict[str, object]:
    return dict(launch.parameters)


# -- <node> ---------------------------------------------------------------------------------------


def test_nodes_are_found_in_the_packages_program_folders(workspace: Path) -> None:
    launch = _launch(
        workspace,
        """<node name="talker" pkg="demo" type="talker.py" output="screen" args="--rate 5 'two words'"/>
           <node name="listener" pkg="demo" type="listener.py" respawn="true"/>
           <node name="relay" pkg="demo" type="relay.py"/>
           <node name="tool" pkg="demo" type="tool.py"/>
           <node name="helper" pkg="other" type="helper.py"/>""",
    )
    programs = {node.name: node.program for node in launch.nodes}
    assert programs == {
        "/talker": workspace / "src" / "talker.py",
        "/listener": workspace / "scripts" / "listener.py",
        "/relay": workspace / "nodes" / "relay.py",
        "/tool": workspace / "src" / "demo" / "tool.py",
        "/helper": workspace.parent / "other_pkg_folder" / "scripts" / "helper.py",
    }
    talker, listener = launch.nodes[0], launch.nodes[1]
    assert talker.args == ("--rate", "5", "two words", "__name:=talker") and not talker.respawn
    assert listener.respawn and launch.warnings == ()


def test_a_node_in_a_group_gets_its_namespace_remaps_and_environment(workspace: Path) -> None:
    launch = _launch(
        workspace,
        """<remap from="scan" to="/base_scan"/>
           <env name="MODE" value="sim"/>
           <group ns="robot1">
             <node name="talker" pkg="demo" type="talker.py">
               <remap from="chatter" to="news"/>
               <env name="EXTRA" value="1"/>
             </node>
             <group ns="/abs"><node name="relay" pkg="demo" type="relay.py" ns="inner"/></group>
           </group>""",
    )
    talker, relay = launch.nodes
    assert talker.name == "/robot1/talker" and talker.launch_name == "robot1/talker"
    assert talker.args == ("scan:=/base_scan", "chatter:=news", "__name:=talker", "__ns:=/robot1")
    assert dict(talker.env) == {"MODE": "sim", "EXTRA": "1"}
    assert relay.name == "/abs/inner/relay" and relay.args[-1] == "__ns:=/abs/inner"


@pytest.mark.parametrize(
    ("body", "match"),
    [
        ('<node name="x" pkg="demo"/>', r"line 2: <node>: the attribute 'type' is required"),
        ('<node name="x" pkg="demo" type="nothing.py"/>', r"package demo has no nothing.py \(looked in src, scripts, nodes, \."),
        ('<node name="x" pkg="demo" type="binary"/>', r"Skydeck runs Python nodes \(a .py file\)"),
        ('<node name="x" pkg="nowhere" type="a.py"/>', r"no package nowhere in .*src \(the folder that holds demo\)"),
        ('<node name="a/b" pkg="demo" type="talker.py"/>', r"invalid name 'a/b'"),
        ('<node name="x" pkg="demo" type="talker.py"/>\n<node name="x" pkg="demo" type="relay.py"/>', r"line 3: .*a second node named /x"),
        ('<node name="x" pkg="demo" type="talker.py" respawn="maybe"/>', r"respawn='maybe' is not true or false"),
        ('<node name="x" pkg="demo" type="talker.py"><group/></node>', r"a <node> holds <param>, <rosparam>, <remap> and <env> only"),
        ('<node name="x" pkg="demo" type="talker.py" args="\'open"/>', r"args: No closing quotation"),
    ],
)
def test_node_errors_name_the_file_line_and_problem(workspace: Path, body: str, match: str) -> None:
    error = _fails(workspace, body, match)
    assert str(error).startswith(str(workspace / "launch" / "test.launch") + ": line ")


def test_attributes_skydeck_does_not_use_are_warnings(workspace: Path) -> None:
    launch = _launch(
        workspace,
        """<node name="x" pkg="demo" type="talker.py" required="true" colour="red"/>
           <machine name="m" address="localhost"/>
           <test test-name="t" pkg="demo" type="talker.py"/>""",
    )
    assert launch.warnings == (
        "test.launch:2: <node>: required='true' is not used by Skydeck; ignored",
        "test.launch:2: <node>: unknown attribute 'colour' ignored (it takes: name, pkg, type, args, ns, respawn, output, if, unless)",
        "test.launch:3: <machine>: skipped: every node runs on this machine by skydeck launch",
        "test.launch:4: <test>: skipped: tests are not run by skydeck launch",
    )


# -- <param> and <rosparam> ----------------------------------------------------------------------


def test_params_global_relative_private_and_typed(workspace: Path) -> None:
    (workspace / "launch" / "motd.txt").write_text("hello\n")
    launch = _launch(
        workspace,
        """<param name="/use_sim_time" value="true"/>
           <param name="rate" value="10"/>
           <param name="gain" value="0.5"/>
           <param name="label" value="odom"/>
           <param name="forced" type="str" value="42"/>
           <param name="ratio" type="double" value="2"/>
           <param name="on" type="bool" value="1"/>
           <param name="tree" type="yaml" value="{a: 1, b: [x, y]}"/>
           <param name="motd" textfile="motd.txt"/>
           <group ns="robot1">
             <param name="speed" value="0.3"/>
             <node name="ai" pkg="demo" type="talker.py">
               <param name="visit_radius" value="0.4"/>
               <param name="~private_too" value="1"/>
               <param name="/absolute" value="yes"/>
             </node>
           </group>""",
    )
    assert _parameters(launch) == {
        "/use_sim_time": True,
        "/rate": 10,
        "/gain": 0.5,
        "/label": "odom",
        "/forced": "42",
        "/ratio": 2.0,
        "/on": True,
        "/tree": {"a": 1, "b": ["x", "y"]},
        "/motd": "hello\n",
        "/robot1/speed": 0.3,
        "/robot1/ai/visit_radius": 0.4,
        "/robot1/ai/private_too": 1,
        "/absolute": "yes",
    }


@pytest.mark.parametrize(
    ("body", "match"),
    [
        ('<param name="x"/>', r"param x: give exactly one of value=, textfile= \(got 0\)"),
        ('<param name="x" value="1" textfile="f"/>', r"give exactly one of value=, textfile= \(got 2\)"),
        ('<param name="x" command="date"/>', r"command= is not provided by Skydeck"),
        ('<param name="~x" value="1"/>', r"a private name \(~\) only means something inside a <node>"),
        ('<param name="x" type="int" value="ten"/>', r"value 'ten' is not of type int"),
        ('<param name="x" type="float" value="1"/>', r"type 'float' is not one of str, int, double, bool, yaml, auto"),
        ('<param name="bad-name" value="1"/>', r"'bad-name' is not a name"),
        ('<param name="x" type="yaml" value="null"/>', r"/x: None is not a parameter value"),
        ('<param name="x" textfile="missing.txt"/>', r"textfile .*missing.txt: cannot read it"),
    ],
)
def test_param_errors(workspace: Path, body: str, match: str) -> None:
    _fails(workspace, body, match)


def test_rosparam_loads_yaml_inline_and_from_files_merged_by_leaves(workspace: Path) -> None:
    (workspace / "launch" / "gains.yaml").write_text("p: 1.0\nnested: {i: 2}\n")
    launch = _launch(
        workspace,
        """<arg name="speed" default="0.5"/>
           <rosparam>
             limits: {max_speed: 8.0, altitude: 3}
             names: [a, b]
           </rosparam>
           <rosparam command="load" file="$(find demo)/launch/gains.yaml" ns="gains"/>
           <rosparam param="single">[1, 2, 3]</rosparam>
           <rosparam subst_value="true">from_arg: $(arg speed)</rosparam>
           <node name="ctl" pkg="demo" type="talker.py">
             <rosparam>{rate: 30}</rosparam>
           </node>""",
    )
    assert _parameters(launch) == {
        "/limits/max_speed": 8.0,
        "/limits/altitude": 3,
        "/names": ["a", "b"],
        "/gains/p": 1.0,
        "/gains/nested/i": 2,
        "/single": [1, 2, 3],
        "/from_arg": 0.5,
        "/ctl/rate": 30,
    }


@pytest.mark.parametrize(
    ("body", "match"),
    [
        ('<rosparam command="delete" param="x"/>', r"command='delete' is not provided by Skydeck \(it loads parameters only\)"),
        ("<rosparam>a: [1, 2</rosparam>", r"line 2: <rosparam>: its text: YAML syntax error at line 1"),
        ("<rosparam>[1, 2]</rosparam>", r"without param=, the YAML must be a mapping"),
        ('<rosparam file="nope.yaml"/>', r"file .*nope.yaml: cannot read it"),
    ],
)
def test_rosparam_errors(workspace: Path, body: str, match: str) -> None:
    _fails(workspace, body, match)


# -- <arg>, substitutions, if/unless -----------------------------------------------------------


def test_args_defaults_fixed_values_and_the_command_line(workspace: Path) -> None:
    body = """<arg name="rate" default="10"/>
              <arg name="fixed" value="odom"/>
              <arg name="needed"/>
              <param name="rate" value="$(arg rate)"/>
              <param name="frame" value="$(arg fixed)"/>
              <param name="needed" value="$(arg needed)"/>"""
    assert _parameters(_launch(workspace, body, needed="x")) == {"/rate": 10, "/frame": "odom", "/needed": "x"}
    assert _parameters(_launch(workspace, body, needed="x", rate="20"))["/rate"] == 20
    _fails(workspace, body, r"line 7: <param>: \$\(arg needed\): the arg has no value: pass needed:=VALUE")
    _fails(workspace, body, r"arg fixed has a fixed value= and cannot be set from outside", needed="x", fixed="map")
    _fails(workspace, body, r"test.launch: typo: given but not declared here", needed="x", typo="1")


@pytest.mark.parametrize(
    ("body", "match"),
    [
        ('<param name="x" value="$(arg nope)"/>', r'\$\(arg nope\): no <arg name="nope"> is declared before it'),
        ('<arg name="a" default="1"/><arg name="a" default="2"/>', r"arg a is declared twice \(first on line 2\)"),
        ('<arg name="a" default="1" value="2"/>', r"give default= \(settable\) or value= \(fixed\), not both"),
        ('<param name="x" value="$(eval 1 + 1)"/>', r"\$\(eval ...\) is not provided by Skydeck"),
        ('<param name="x" value="$(magic)"/>', r"\$\(magic\) is not a substitution Skydeck knows"),
        ('<param name="x" value="$(env SKYDECK_SURELY_UNSET_VARIABLE)"/>', r"the variable is not set"),
        ('<param name="x" value="$(find nowhere)"/>', r"\$\(find nowhere\): no package nowhere"),
        ('<group if="maybe"/>', r"if='maybe' is not true or false"),
        ('<group if="true" unless="false"/>', r"give `if` or `unless`, not both"),
    ],
)
def test_substitution_and_arg_errors(workspace: Path, body: str, match: str) -> None:
    _fails(workspace, body, match)


def test_substitutions_and_if_unless(workspace: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOT_NAME", "bot7")
    launch = _launch(
        workspace,
        """<arg name="sim" default="true"/>
           <param name="robot" value="$(env ROBOT_NAME)"/>
           <param name="fallback" value="$(optenv SKYDECK_SURELY_UNSET_VARIABLE default text)"/>
           <param name="here" value="$(dirname)"/>
           <param name="pkg" value="$(find demo)"/>
           <param name="anon1" value="$(anon viewer)"/>
           <param name="anon2" value="$(anon viewer)"/>
           <param name="when_sim" value="1" if="$(arg sim)"/>
           <param name="when_real" value="1" unless="$(arg sim)"/>
           <group unless="$(arg sim)"><node name="real" pkg="demo" type="talker.py"/></group>
           <node name="simulated" pkg="demo" type="talker.py" if="$(arg sim)"/>""",
    )
    values = _parameters(launch)
    assert values["/robot"] == "bot7" and values["/fallback"] == "default text"
    assert values["/here"] == str(workspace / "launch") and values["/pkg"] == str(workspace)
    assert values["/anon1"] == values["/anon2"] and str(values["/anon1"]).startswith("viewer_")
    assert "/when_sim" in values and "/when_real" not in values
    assert [node.name for node in launch.nodes] == ["/simulated"]


# -- <include> ---------------------------------------------------------------------------------------


def test_includes_take_args_namespaces_and_find(workspace: Path) -> None:
    (workspace / "launch" / "part.launch").write_text(
        """<launch>
             <arg name="who"/>
             <arg name="rate" default="1"/>
             <node name="$(arg who)" pkg="demo" type="talker.py"><param name="rate" value="$(arg rate)"/></node>
           </launch>"""
    )
    launch = _launch(
        workspace,
        """<arg name="rate" default="5"/>
           <include file="part.launch"><arg name="who" value="first"/></include>
           <include file="$(find demo)/launch/part.launch" ns="team">
             <arg name="who" value="second"/><arg name="rate" value="$(arg rate)"/>
           </include>
           <group ns="g"><include file="part.launch" pass_all_args="true"><arg name="who" value="third"/></include></group>""",
    )
    assert [node.name for node in launch.nodes] == ["/first", "/team/second", "/g/third"]
    assert _parameters(launch) == {"/first/rate": 1, "/team/second/rate": 5, "/g/third/rate": 5}


def test_include_errors(workspace: Path) -> None:
    (workspace / "launch" / "part.launch").write_text('<launch><arg name="who" default="x"/></launch>')
    (workspace / "launch" / "loop.launch").write_text('<launch><include file="loop.launch"/></launch>')
    _fails(workspace, '<include file="missing.launch"/>', r"line 2: <include>: no such file .*missing.launch")
    _fails(workspace, '<include file="part.launch"><arg name="typo" value="1"/></include>', r"part.launch: typo: given but not declared")
    _fails(workspace, '<include file="loop.launch"/>', r"loop.launch: line 1: <include>: includes nest deeper than 16")
    _fails(workspace, '<include file="part.launch"><node name="x" pkg="demo" type="talker.py"/></include>', r"holds <arg> and <env> only")


# -- the file itself --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("<launch>\n  <node name='x'\n</launch>\n", r"line 3, column 1: not valid XML: not well-formed"),
        ("<ros><node/></ros>", r"line 1: the top element is <ros>, expected <launch>"),
        ("", r"not valid XML: no element found"),
        ("<launch><nodes/></launch>", r"line 1: <nodes>: not a tag Skydeck knows here \(it reads: arg, param, rosparam, node, group"),
        ("<launch><!-- a -- b --></launch>", r"not valid XML"),
    ],
)
def test_file_errors(workspace: Path, text: str, match: str) -> None:
    path = workspace / "launch" / "bad.launch"
    path.write_text(text)
    with pytest.raises(LaunchFileError, match=match):
        load_roslaunch_file(path)


def test_a_missing_file_is_one_line(tmp_path: Path) -> None:
    with pytest.raises(LaunchFileError, match=r"nothing.launch: no such launch file"):
        load_roslaunch_file(tmp_path / "nothing.launch")


# -- what the supervisor gets ---------------------------------------------------------------------


def test_the_spec_puts_the_core_first_only_when_asked_and_nodes_after_the_simulators_port(workspace: Path) -> None:
    launch = _launch(
        workspace,
        """<node name="a" pkg="demo" type="talker.py" args="{literal}"/>
           <group ns="ns"><node name="b" pkg="demo" type="relay.py" respawn="true"/></group>""",
    )
    beside = launch.spec(start_core=False)
    assert [(n.name, n.port_offset) for n in beside.nodes] == [("a", NODE_PORT_OFFSET), ("ns/b", NODE_PORT_OFFSET + 1)]
    assert beside.nodes[0].args == ("{{literal}}", "__name:=a")  # braces stay text, not placeholders
    assert beside.nodes[1].respawn and not beside.nodes[0].respawn
    alone = launch.spec(start_core=True)
    assert [(n.name, n.run, n.port_offset) for n in alone.nodes][0] == ("core", "core", 0)


def test_a_node_named_core_clashes_only_with_a_core_the_launch_starts(workspace: Path) -> None:
    launch = _launch(workspace, '<node name="core" pkg="demo" type="talker.py"/>')
    assert launch.spec(start_core=False).nodes[0].name == "core"
    with pytest.raises(LaunchFileError, match="a node named /core clashes with skydeck launch's own"):
        launch.spec(start_core=True)


def test_no_core_answers_on_a_free_port() -> None:
    from services.runtime.ports import free_port_block

    assert not core_answers(f"http://127.0.0.1:{free_port_block(1)}")


@pytest.mark.timeout(60)
def test_a_roslaunch_file_starts_a_core_when_none_runs(workspace: Path) -> None:
    import os
    import signal
    import sys

    from services.launch.background import BackgroundProcess
    from services.runtime.ports import free_port_block

    (workspace / "src" / "talker.py").write_text(
        'import rospy\nrospy.init_node("talker")\nrospy.loginfo("rate is %s", rospy.get_param("~rate"))\nrospy.spin()\n'
    )
    path = workspace / "launch" / "alone.launch"
    path.write_text('<launch><node name="talker" pkg="demo" type="talker.py"><param name="rate" value="5"/></node></launch>')
    base = free_port_block(3)
    process = BackgroundProcess(
        [sys.executable, "-m", "services.cli", "launch", "--base-port", str(base), "--rosbridge-port", "0",
         "--foxglove-port", "0", str(path)],
        name="skydeck launch alone.launch",
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )  # fmt: skip
    try:
        process.wait_for_line("rate is 5", 45)
        assert f"[launch] starting core :{base}, talker :{base + NODE_PORT_OFFSET}" in "\n".join(process.lines)
    finally:
        assert process.stop(signal.SIGINT, timeout_s=20)
    assert not any("Traceback" in line for line in process.lines), process.tail(20)
