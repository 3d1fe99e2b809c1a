"""The core's ROS 1 parameter server: the tree's semantics, its API, and the SDK's client."""

from __future__ import annotations

import httpx
import pytest

from services.core.parameter_server import ParameterTree
from services.runtime.http_client import HttpClient
from services.runtime.rosparam import RosParamClient, RosParamError
from tests.conftest import CoreProcess

pytestmark = [pytest.mark.timeout(30)]


def test_namespaces_read_as_mappings_and_mappings_set_subtrees() -> None:
    tree = ParameterTree()
    tree.set("/ai/visit_radius", 0.4)
    tree.set("/ai/gains", {"p": 1.0, "d": [0.1, 0.2]})
    assert tree.get("/ai") == {"visit_radius": 0.4, "gains": {"p": 1.0, "d": [0.1, 0.2]}}
    assert tree.get("/ai/gains/d") == [0.1, 0.2]
    assert tree.get("/") == {"ai": {"visit_radius": 0.4, "gains": {"p": 1.0, "d": [0.1, 0.2]}}}
    tree.set("/ai/gains", {"i": 2})  # a mapping replaces the subtree, as rosmaster's setParam
    assert tree.get("/ai/gains") == {"i": 2}
    tree.set("/ai/visit_radius/inner", True)  # a plain value becomes a namespace
    assert tree.get("/ai/visit_radius") == {"inner": True}


def test_reads_are_copies_and_deletes_take_the_subtree() -> None:
    tree = ParameterTree()
    tree.set("/a/b", [1, 2])
    tree.get("/a/b").append(3)
    assert tree.get("/a/b") == [1, 2]
    tree.delete("/a")
    with pytest.raises(KeyError):
        tree.get("/a/b")
    with pytest.raises(KeyError):
        tree.delete("/a")


@pytest.mark.parametrize(
    ("name", "value", "problem"),
    [
        ("relative", 1, "must be absolute"),
        ("/a-b", 1, "'a-b' is not a name"),
        ("/x", None, "is not a parameter value"),
        ("/x", {"bad key": 1}, "'bad key' is not a parameter name"),
        ("/", 3, "root / can only be set to a mapping"),
    ],
)
def test_bad_names_and_values_are_refused(name: str, value: object, problem: str) -> None:
    with pytest.raises(ValueError, match=problem):
        ParameterTree().set(name, value)


async def test_the_client_sets_gets_and_deletes_through_the_core(core: CoreProcess) -> None:
    http = HttpClient()
    server = RosParamClient(http, core.url)
    try:
        await server.set("/use_sim_time", True)
        await server.set("/ai", {"visit_radius": 0.4})
        assert await server.get("/use_sim_time") is True
        assert await server.get("/ai/visit_radius") == 0.4
        assert (await server.get("/")) == {"use_sim_time": True, "ai": {"visit_radius": 0.4}}
        await server.delete("/ai/visit_radius")
        with pytest.raises(KeyError):
            await server.get("/ai/visit_radius")
        with pytest.raises(KeyError):
            await server.delete("/ai/visit_radius")
        with pytest.raises(RosParamError, match="refused PUT /x: /x: None is not a parameter value"):
            await server.set("/x", None)
        # A name that is not a ROS name is a 422 on every verb: the schema's pattern says which are.
        async with httpx.AsyncClient(timeout=10) as plain:
            for method in ("GET", "PUT", "DELETE"):
                reply = await plain.request(method, core.url + "/api/rosparam/a-b", json={"value": 1})
                assert reply.status_code == 422 and reply.json()["detail"][0]["loc"] == ["path", "name"], method
            # The pattern is parameter_tokens' own: its tokens between any slashes, never a digit first.
            assert (await plain.get(core.url + "/api/rosparam/1a")).status_code == 422
            assert (await plain.get(core.url + "/api/rosparam/no//such_/")).status_code == 404
    finally:
        await http.aclose()


async def test_writes_need_the_token_when_the_core_has_one() -> None:
    core = CoreProcess(token="secret")
    await core.start()
    anonymous, member = HttpClient(), HttpClient(headers={"Authorization": "Bearer secret"})
    try:
        with pytest.raises(RosParamError, match="refused PUT /x"):
            await RosParamClient(anonymous, core.url).set("/x", 1)
        await RosParamClient(member, core.url).set("/x", 1)
        assert await RosParamClient(anonymous, core.url).get("/x") == 1
    finally:
        await anonymous.aclose()
        await member.aclose()
        await core.stop()


async def test_no_core_is_one_line_that_says_so() -> None:
    http = HttpClient()
    try:
        with pytest.raises(RosParamError, match=r"cannot reach the parameter server at http://127.0.0.1:9 .*is the core running"):
            await RosParamClient(http, "http://127.0.0.1:9").get("/x")
    finally:
        await http.aclose()
