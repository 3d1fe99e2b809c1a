"""The table of worlds: a third world is one package and one row, and the simulator's entry,
the core's /api/config and the launcher read the row; the shipped worlds' rows are whole."""

from __future__ import annotations

from collections.abc import Iterator

import httpx
import pytest

from services.launch import find_launch_file, load_launch_file
from services.runtime import NodeSettings
from shared_models.geometry_msgs import PoseArray
from shared_models.ros_workshop import SimWorld
from sim_server.camera_stream import RAW_TOPIC
from sim_server.node import _parser, world_settings
from sim_server.worlds import (
    WORLDS,
    UnknownWorld,
    WorldEntry,
    default_world,
    find_world,
    world_options,
)
from tests.conftest import wait_until

pytestmark = pytest.mark.timeout(60)

TINY = WorldEntry(
    name="tiny",
    summary="balls dropped on a ground",
    node="tests.sim_server.tiny.node:BallNode",
    settings="tests.sim_server.tiny.settings:BallSettings",
    description="tests.sim_server.tiny.description:DESCRIPTION",
    launch_file="workshop",
)


@pytest.fixture
def tiny_world(monkeypatch: pytest.MonkeyPatch) -> Iterator[WorldEntry]:
    monkeypatch.setitem(WORLDS, "tiny", TINY)
    yield TINY


async def test_a_third_world_is_a_package_and_a_row(tiny_world: WorldEntry, core, start_node) -> None:
    entry, sim = world_settings(["--world", "tiny", "--balls", "2", "--seed", "3", "--speed", "max"])
    assert entry is tiny_world and (sim.balls, sim.seed, sim.speed) == (2, 3, None)  # type: ignore[attr-defined]
    node_type = entry.node_type()
    node = await start_node(lambda settings: node_type(sim, settings))
    async with httpx.AsyncClient(timeout=5.0) as http:
        await wait_until(lambda: node.world.time_s > 1.0, what="the ball world to step")
        balls = PoseArray.model_validate((await http.get(core.url + "/tiny/balls")).json())
        assert len(balls.poses) == 2 and balls.poses[0].position.z < 0.5, "the balls fell to the ground"
        world = SimWorld.model_validate((await http.get(core.url + "/simulator/world")).json())
        assert (world.world, world.seed) == ("tiny", 3)
        assert (await http.get(core.url + "/clock")).status_code == 200
        config = (await http.get(core.url + "/api/config")).json()["worlds"]
    assert config["tiny"] == {"ball_radius_m": 0.2, "topics": {"balls": "/tiny/balls"}, "services": {}}
    assert {"drone", "robot"} <= set(config)
    assert node.get_parameter("balls").value == 2 and node.describe_parameter("balls").read_only
    assert node.camera.raw.topic_name == RAW_TOPIC  # the floor's camera, on the floor's names


def test_the_entry_and_the_launcher_know_a_new_worlds_options(tiny_world: WorldEntry) -> None:
    help_text = " ".join(_parser().format_help().split())  # as read, wherever argparse wraps it
    assert "--balls" in help_text and "tiny: balls dropped on a ground" in help_text
    assert world_options()["balls"].world == "tiny"
    with pytest.raises(SystemExit):
        world_settings(["--world", "tiny", "--boxes", "3"])  # the drone world's


def test_an_unknown_world_says_which_there_are() -> None:
    with pytest.raises(UnknownWorld, match=r"no world 'moon': the worlds are drone, robot, soccer"):
        find_world("moon")
    assert find_world(None) is default_world() is WORLDS["drone"]


@pytest.mark.parametrize("name", list(WORLDS))
def test_each_shipped_world_is_whole(name: str) -> None:
    entry = WORLDS[name]
    description = entry.describe()
    settings = entry.settings_type()
    assert description.constants and description.topics
    assert set(settings.own_options()) <= set(world_options())
    spec = load_launch_file(find_launch_file(entry.launch_file), {})
    (sim,) = [node for node in spec.nodes if node.run == "sim"]
    world_flag = sim.args[sim.args.index("--world") + 1] if "--world" in sim.args else default_world().name
    assert world_flag == name, "the world's launch file starts the world"
    for option in settings.own_options():
        assert spec.uses(option), f"{entry.launch_file} passes --{option} on"


def test_a_node_gets_its_worlds_settings() -> None:
    # The row's node class takes the row's settings class: the entry's one call.
    for entry in WORLDS.values():
        node = entry.node_type()(entry.settings_type()(seed=1), NodeSettings(port=0))  # type: ignore[call-arg]
        try:
            assert entry.name == node.WORLD_NAME
        finally:
            node.world.close()
