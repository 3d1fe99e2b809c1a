"""Assignment files: the shipped ones load; a malformed one is one line naming the file and field."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.builtin_nodes import BUILTIN_NODES
from services.grading.assignment import AssignmentError, hidden_seed, load_assignment

SHIPPED = sorted(Path("examples/assignments").glob("*.yaml"))
BEHAVIOURS = ["drive_square", "estop", "wall_follower", "person_follower", "obstacle_avoider", "fsm", "drone_mission"]

GOOD = """\
assignment: wall_follower
world: robot
duration_s: 10
seeds: {visible: [1, 2], hidden: 2}
criteria:
  - name: wall_follower.band_fraction
    params: {distance: 0.5}
    min: 0.8
"""


def test_an_assignment_is_shipped_for_every_behaviour_named_after_it() -> None:
    assert sorted(path.stem for path in SHIPPED) == sorted(BEHAVIOURS)
    for path in SHIPPED:
        assignment = load_assignment(path)
        assert assignment.assignment == path.stem
        assert assignment.reference in BUILTIN_NODES
        assert assignment.seeds.visible and assignment.seeds.hidden > 0


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "a.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("change", "says"),
    [
        (("world: robot", "world: moon"), "world: no world 'moon'"),
        (("duration_s: 10", "duration_s: -1"), "duration_s: Input should be greater than 0"),
        (("duration_s: 10\n", "duration_s: 10\ncolour: blue\n"), "colour: not a field of an assignment"),
        (("world: robot\n", ""), "world: missing"),
        (("    min: 0.8", "    min: 0.8\n    max: 0.9"), "give exactly one threshold"),
        (("    min: 0.8", "    params: {}"), "criteria.0"),
        (("wall_follower.band_fraction", "wall_follower.speed"), "no criterion 'wall_follower.speed'"),
        (("{distance: 0.5}", "{distance: -1}"), "wall_follower.band_fraction: params.distance: Input should be greater than 0"),
        (("{distance: 0.5}", "{range: 2}"), "params.range: Extra inputs are not permitted"),
        (("world: robot\n", "world: robot\noptions: {boxes: 3}\n"), "options.boxes: not an option of the robot world (its options: robots, obstacles)"),
        (("world: robot\n", "world: robot\noptions: {obstacles: 99}\n"), "options.obstacles: Input should be less than or equal to 8"),
        (("world: robot", "world: drone"), "scores the robot world, not drone"),
        (("visible: [1, 2]", "visible: [1, 1]"), "seeds.visible: a seed is listed twice"),
        (("visible: [1, 2]", "visible: [-3]"), "seeds.visible: seed -3 is outside"),
        (("duration_s: 10\n", "duration_s: 10\nnodes: [sim]\n"), "nodes: 'sim' is not a built-in node"),
        (("assignment: wall_follower", "assignment: Wall Follower"), "assignment: String should match pattern"),
    ],
)
def test_a_malformed_assignment_is_one_line_naming_the_file_and_field(tmp_path: Path, change: tuple[str, str], says: str) -> None:
    old, new = change
    assert old in GOOD
    path = write(tmp_path, GOOD.replace(old, new, 1))
    with pytest.raises(AssignmentError) as raised:
        load_assignment(path)
    message = str(raised.value)
    assert message.startswith(f"{path}: ")
    assert says in message
    assert "\n" not in message


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("criteria: [unclosed", "YAML syntax error at line 1"),
        ("- a list\n- of things\n", "an assignment is a mapping of fields"),
        ("", "an assignment is a mapping of fields"),
    ],
)
def test_a_file_that_is_not_an_assignment(tmp_path: Path, text: str, says: str) -> None:
    with pytest.raises(AssignmentError, match=says):
        load_assignment(write(tmp_path, text))


def test_a_missing_file(tmp_path: Path) -> None:
    with pytest.raises(AssignmentError, match="no such assignment file"):
        load_assignment(tmp_path / "nope.yaml")


def test_hidden_seeds_need_the_secret_and_are_the_same_for_the_same_secret(tmp_path: Path) -> None:
    assignment = load_assignment(write(tmp_path, GOOD))
    with pytest.raises(AssignmentError, match="SKYDECK_GRADE_SECRET"):
        assignment.seeds_for("hidden")
    seeds = assignment.seeds_for("hidden", secret="s3cret")
    assert seeds == assignment.seeds_for("hidden", secret="s3cret")
    assert len(set(seeds)) == 2 and all(0 <= seed < 2**32 for seed in seeds)
    assert seeds != assignment.seeds_for("hidden", secret="another")
    assert seeds[0] == hidden_seed("s3cret", "wall_follower", 0)
    assert assignment.seeds_for("visible") == [1, 2]
    none = load_assignment(write(tmp_path, GOOD.replace("hidden: 2", "hidden: 0")))
    with pytest.raises(AssignmentError, match="no hidden seeds"):
        none.seeds_for("hidden", secret="s3cret")
