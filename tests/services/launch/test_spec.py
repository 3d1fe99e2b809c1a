"""Launch files: the default one, and one clear line for every kind of mistake."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from services.launch import (
    LaunchError,
    LaunchFileError,
    LaunchSpec,
    NodeSpec,
    default_launch_file,
    load_launch_file,
)


def _write(tmp_path: Path, text: str, name: str = "launch.yaml") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def _problem(path: Path) -> str:
    """The one-line message for a bad launch file, checked for its shape."""
    with pytest.raises(LaunchFileError) as caught:
        load_launch_file(path)
    message = str(caught.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: ")
    assert caught.value.path == path
    assert isinstance(caught.value, LaunchError)
    return caught.value.problem


_GOOD = """\
    nodes:
      - name: core
        run: core
        port_offset: 0
      - name: sim
        run: sim
        port_offset: 1
        args: ["--speed", "{speed}", "--seed", "{seed}"]
"""


# --- the default launch file ----------------------------------------------------------------


def test_default_launch_file_is_the_workshop_system() -> None:
    spec = load_launch_file(default_launch_file(), {})
    assert spec.names == ("core", "sim", "perception", "control", "ai")
    assert [node.port_offset for node in spec.nodes] == [0, 1, 2, 3, 4]
    assert [node.run for node in spec.nodes] == ["core", "sim", "perception", "control", "ai"]
    assert spec.nodes[0].is_core
    assert spec.nodes[1].args == ("--speed", "{speed}", "--seed", "{seed}", "--boxes", "{boxes}")
    assert all(node.respawn for node in spec.nodes)


def test_default_launch_file_ships_with_the_package() -> None:
    path = default_launch_file()
    assert path.name == "workshop.yaml"
    assert path.parent == Path(__file__).parents[3] / "services" / "launch"


# --- good files -----------------------------------------------------------------------------


def test_fields_and_defaults(tmp_path: Path) -> None:
    spec = load_launch_file(_write(tmp_path, _GOOD))
    core, sim = spec.nodes
    assert core == NodeSpec(name="core", run="core", port_offset=0)
    assert core.args == () and core.env == {} and core.respawn is True
    assert core.ready_timeout_s == 20.0
    assert sim.args == ("--speed", "{speed}", "--seed", "{seed}")


def test_numbers_in_args_and_env_become_strings(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: sim, run: sim, port_offset: 1, args: ["--boxes", 8], env: {SKYDECK_X: 1.5}}
        """,
    )
    node = load_launch_file(path).nodes[0]
    assert node.args == ("--boxes", "8")
    assert node.env == {"SKYDECK_X": "1.5"}


def test_relative_run_paths_resolve_against_the_launch_file(tmp_path: Path) -> None:
    (tmp_path / "nodes").mkdir()
    (tmp_path / "nodes" / "mine.py").write_text("print('hi')\n")
    (tmp_path / "launch").mkdir()
    path = _write(
        tmp_path / "launch",
        """\
        nodes:
          - {name: mine, run: ../nodes/mine.py, port_offset: 5}
        """,
    )
    assert load_launch_file(path).nodes[0].run == str((tmp_path / "nodes" / "mine.py").resolve())


def test_literal_braces_are_allowed(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: sim, run: sim, port_offset: 1, args: ['{{"a": 1}}'], env: {X: "{base_port}"}}
        """,
    )
    assert load_launch_file(path).nodes[0].args == ('{{"a": 1}}',)


# --- one line per mistake -------------------------------------------------------------------


def test_missing_file(tmp_path: Path) -> None:
    assert _problem(tmp_path / "nope.yaml") == "no such launch file"


def test_a_folder_is_not_a_launch_file(tmp_path: Path) -> None:
    assert "folder" in _problem(tmp_path)


def test_yaml_syntax_error_names_the_line(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - name: core
            run: core: oops
        """,
    )
    problem = _problem(path)
    assert problem.startswith("YAML syntax error at line 3, column")


def test_empty_file(tmp_path: Path) -> None:
    assert "empty" in _problem(_write(tmp_path, ""))


def test_top_level_must_be_a_mapping(tmp_path: Path) -> None:
    assert "got a list" in _problem(_write(tmp_path, "- name: core\n"))


def test_no_nodes(tmp_path: Path) -> None:
    assert _problem(_write(tmp_path, "nodes: []\n")) == "nodes: a launch needs at least one node"


def test_unknown_field_names_its_place_and_the_allowed_fields(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: core, run: core, port_offset: 0}
          - {name: sim, run: sim, port_offset: 1, colour: red}
        """,
    )
    problem = _problem(path)
    assert problem.startswith("nodes[1].colour: unknown field (allowed: name, package, run, port_offset,")


def test_unknown_top_level_field(tmp_path: Path) -> None:
    problem = _problem(_write(tmp_path, textwrap.dedent(_GOOD) + "verbose: true\n"))
    assert problem == "verbose: unknown field (allowed: arguments, nodes)"


def test_missing_field(tmp_path: Path) -> None:
    problem = _problem(_write(tmp_path, "nodes:\n  - {name: core, port_offset: 0}\n"))
    assert problem == "nodes[0].run: missing (required)"


def test_negative_port_offset(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: core, run: core, port_offset: 0}
          - {name: sim, run: sim, port_offset: 1}
          - {name: ai, run: ai, port_offset: -2}
        """,
    )
    assert _problem(path) == "nodes[2].port_offset: Input should be greater than or equal to 0"


def test_duplicate_port_offset(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: core, run: core, port_offset: 0}
          - {name: sim, run: sim, port_offset: 1}
          - {name: ai, run: ai, port_offset: 1}
        """,
    )
    assert _problem(path) == "nodes[2].port_offset: 1 is already used by nodes[1] (sim)"


def test_duplicate_name(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: sim, run: sim, port_offset: 1}
          - {name: sim, run: ai, port_offset: 2}
        """,
    )
    assert _problem(path) == "nodes[1].name: 'sim' is already the name of nodes[0]"


def test_two_cores(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: core, run: core, port_offset: 0}
          - {name: core2, run: core, port_offset: 9}
        """,
    )
    assert _problem(path) == "nodes[1].run: only one node may run the core (nodes[0] does)"


def test_unknown_placeholder(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: core, run: core, port_offset: 0}
          - {name: sim, run: sim, port_offset: 1, args: ["--speed", "{speed}", "--seed", "{sed}"]}
        """,
    )
    problem = _problem(path)
    assert problem.startswith(
        "nodes[1].args[3]: unknown placeholder {sed} in '{sed}'; known: {speed},"
    )


def test_unknown_placeholder_in_env(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - {name: sim, run: sim, port_offset: 1, env: {SKYDECK_SIM_SEED: "{port}"}}
        """,
    )
    assert _problem(path).startswith("nodes[0].env.SKYDECK_SIM_SEED: unknown placeholder {port}")


def test_placeholder_with_a_format_is_refused(tmp_path: Path) -> None:
    path = _write(
        tmp_path, 'nodes:\n  - {name: sim, run: sim, port_offset: 1, args: ["{speed:.1f}"]}\n'
    )
    assert "take no format" in _problem(path)


def test_unbalanced_brace(tmp_path: Path) -> None:
    path = _write(tmp_path, 'nodes:\n  - {name: sim, run: sim, port_offset: 1, args: ["{speed"]}\n')
    problem = _problem(path)
    assert problem.startswith("nodes[0].args[0]: ")
    assert "literal brace" in problem


def test_unquoted_placeholder_gets_a_hint(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """\
        nodes:
          - name: sim
            run: sim
            port_offset: 1
            args: [--speed, {speed}]
        """,
    )
    assert (
        _problem(path) == 'nodes[0].args[1]: a placeholder must be quoted in YAML: write "{speed}"'
    )


def test_bad_name(tmp_path: Path) -> None:
    path = _write(tmp_path, "nodes:\n  - {name: my node, run: sim, port_offset: 1}\n")
    assert _problem(path).startswith("nodes[0].name: String should match pattern")


def test_reserved_name(tmp_path: Path) -> None:
    path = _write(tmp_path, "nodes:\n  - {name: launch, run: sim, port_offset: 1}\n")
    assert _problem(path) == "nodes[0].name: the name 'launch' is reserved; choose another"


def test_unknown_run(tmp_path: Path) -> None:
    path = _write(tmp_path, "nodes:\n  - {name: sim, run: simulator, port_offset: 1}\n")
    assert _problem(path).startswith(
        "nodes[0].run: 'simulator' is neither a built-in (core, sim, perception, control, ai, teleop,"
    )


def test_missing_node_file(tmp_path: Path) -> None:
    path = _write(tmp_path, "nodes:\n  - {name: mine, run: mine.py, port_offset: 5}\n")
    assert _problem(path) == f"nodes[0].run: no such node file {tmp_path.resolve() / 'mine.py'}"


def test_bad_env_name(tmp_path: Path) -> None:
    path = _write(tmp_path, "nodes:\n  - {name: sim, run: sim, port_offset: 1, env: {A=B: x}}\n")
    assert _problem(path).startswith("nodes[0].env.A=B.[key]: String should match pattern")


def test_several_errors_are_counted_not_listed(tmp_path: Path) -> None:
    path = _write(
        tmp_path, "nodes:\n  - {name: core, run: core, port_offset: -1, respawn: maybe}\n"
    )
    assert _problem(path).endswith("(and 1 more)")


def test_the_model_is_frozen() -> None:
    spec = LaunchSpec(nodes=(NodeSpec(name="core", run="core", port_offset=0),))
    with pytest.raises(ValueError):
        spec.nodes[0].port_offset = 3  # type: ignore[misc]
