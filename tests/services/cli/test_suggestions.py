"""A mistyped verb, topic, service or node: one line that says so, with the nearest names."""

from __future__ import annotations

import asyncio
import os
import signal
import sys

import pytest

from services.cli.suggestions import did_you_mean, nearest
from tests.services.cli.test_cli import Talker, skydeck

DRONE_NAMES = [
    "/drone/pose",
    "/drone/cmd_vel",
    "/control/take_off",
    "/control/land",
    "/clock",
    "/rosout",
]


def test_the_nearest_names_are_the_ones_a_letter_or_two_away() -> None:
    assert nearest("/drone/pos", DRONE_NAMES) == ["/drone/pose"]
    assert nearest("/drone/poze", DRONE_NAMES) == ["/drone/pose"]
    assert nearest("/control/take_of", DRONE_NAMES) == ["/control/take_off"]
    assert nearest("/control/tkae_off", DRONE_NAMES) == ["/control/take_off"]
    assert nearest("/pose", DRONE_NAMES) == ["/drone/pose"]
    assert nearest("/simulator/boxes", DRONE_NAMES) == []  # nothing near: no guess
    assert nearest("/drone/pose", DRONE_NAMES) == []  # the name itself is not a suggestion
    assert did_you_mean("topc", ["topic", "service"], quote=True) == " (did you mean 'topic'?)"
    assert did_you_mean("xyz", ["topic", "service"]) == ""


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["topc", "list"], "invalid choice: 'topc' (choose from 'core', 'run', 'topic', "),
        (["topic", "lst"], "did you mean 'list'?"),
        (["servce", "call", "/x"], "did you mean 'service'?"),
        (["param", "gett", "/n", "p"], "did you mean 'get'?"),
    ],
)
async def test_a_mistyped_verb_suggests_the_nearest(core, args: list[str], expected: str) -> None:
    status, out, err = await skydeck(core.url, *args)
    assert status == 2 and out == ""
    assert expected in err.splitlines()[-1] and "did you mean" in err.splitlines()[-1], err


async def test_a_verb_nothing_resembles_gets_argparse_s_line_alone(core) -> None:
    status, _, err = await skydeck(core.url, "xyzzy")
    assert status == 2 and err.splitlines()[-1].startswith(
        "skydeck: error: argument COMMAND: invalid choice: 'xyzzy'"
    )
    assert "did you mean" not in err


async def test_a_bounded_echo_of_a_missing_topic_fails_with_the_nearest_names(
    core, start_node
) -> None:
    await start_node(Talker)
    status, out, err = await skydeck(core.url, "topic", "echo", "/my_pont", "--once")
    assert status == 1 and out == ""
    assert err.strip() == (
        "skydeck: error: unknown topic /my_pont (did you mean /my_point?): see `skydeck topic list`, "
        "or wait for it with --timeout S"
    )
    status, _, err = await skydeck(core.url, "topic", "echo", "/my_pont", "-n", "2")
    assert status == 1 and "did you mean /my_point?" in err
    # asked to wait: it waits (a publisher may come), and says when none did
    status, out, err = await skydeck(
        core.url, "topic", "echo", "/my_pont", "--once", "--timeout", "0.5"
    )
    assert (
        status == 1
        and "(did you mean /my_point?)" in out
        and "no message on /my_pont within 0.5 s" in err
    )


@pytest.mark.parametrize("verb", [["echo"], ["hz"], ["bw"], ["delay"]])
async def test_a_stream_of_a_missing_topic_says_so_once_and_waits(
    core, start_node, verb: list[str]
) -> None:
    await start_node(Talker)
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "services.cli", "topic", *verb, "/my_pont",
        env={**os.environ, "SKYDECK_CORE_URL": core.url, "PYTHONUNBUFFERED": "1"},
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
    )  # fmt: skip
    assert process.stdout is not None
    first = await asyncio.wait_for(process.stdout.readline(), 20)
    assert (
        first.decode().strip()
        == "WARNING: topic [/my_pont] does not appear to be published yet (did you mean /my_point?)"
    )
    with pytest.raises(TimeoutError):  # still waiting for a publisher, saying nothing more
        await asyncio.wait_for(process.wait(), 1.0)
    process.send_signal(signal.SIGINT)
    stdout, stderr = await asyncio.wait_for(process.communicate(), 10)
    assert b"WARNING" not in stdout and b"Traceback" not in stderr  # said once (hz says "no new messages")


async def test_a_topic_subscribed_to_but_unpublished_is_waited_for_without_a_guess(
    core, start_node
) -> None:
    await start_node(Talker)  # it subscribes to /drone/cmd_vel
    status, out, err = await skydeck(
        core.url, "topic", "echo", "/drone/cmd_vel", "--once", "--timeout", "0.3"
    )
    assert out.strip() == "WARNING: topic [/drone/cmd_vel] does not appear to be published yet"
    assert status == 1 and "no message on /drone/cmd_vel within 0.3 s" in err


async def test_a_mistyped_service_topic_or_node_names_the_nearest(core, start_node) -> None:
    await start_node(Talker)
    for args, expected in (
        (["service", "call", "/talker/pnig"], "unknown service /talker/pnig (did you mean /talker/ping?): see `skydeck service list`"),
        (["service", "type", "/talker/pin"], "unknown service /talker/pin (did you mean /talker/ping?): see `skydeck service list`"),
        (["topic", "info", "/my_pointt"], "unknown topic /my_pointt (did you mean /my_point?): see `skydeck topic list`"),
        (["topic", "type", "/mypoint"], "unknown topic /mypoint (did you mean /my_point?): see `skydeck topic list`"),
        (["node", "info", "/talkr"], "unknown node /talkr (did you mean /talker?): see `skydeck node list`"),
        (["service", "call", "/nothing/like/it"], "unknown service /nothing/like/it: see `skydeck service list`"),
    ):  # fmt: skip
        status, _, err = await skydeck(core.url, *args)
        assert status == 1 and err.strip() == f"skydeck: error: {expected}", (args, err)
