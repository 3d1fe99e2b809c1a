"""The AI's landing policy is a parameter: its default the flag's, ``-p landing:=...`` overrides
it, and a value that is no policy is refused with the reason."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from services.ai.node import AiNode, AiSettings
from services.ai.progress import ProgressStore
from services.runtime import NodeSettings, Parameter
from services.runtime.parameters import InvalidParameterValueException
from services.runtime.ros_args import RosArguments, parse_ros_args, set_process_ros_arguments


@pytest.fixture
def ros_args() -> Iterator[None]:
    yield
    set_process_ros_arguments(RosArguments())


def _ai(tmp_path, **kwargs) -> AiNode:
    return AiNode(NodeSettings(port=0), store=ProgressStore(tmp_path), **kwargs)


def test_the_flag_is_the_default_and_an_override_wins(tmp_path, ros_args) -> None:
    assert _ai(tmp_path).get_parameter("landing").value == "beside_last_box"
    assert _ai(tmp_path, ai=AiSettings(landing="home")).get_parameter("landing").value == "home"
    set_process_ros_arguments(parse_ros_args(["-p", "ai:landing:=home"]))
    assert _ai(tmp_path).get_parameter("landing").value == "home"


def test_a_landing_that_is_no_policy_is_refused_with_the_reason(tmp_path, ros_args) -> None:
    ai = _ai(tmp_path)
    [result] = ai.set_parameters([Parameter("landing", value="moon")])
    assert not result.successful and result.reason == "landing must be one of beside_last_box, home; got 'moon'"
    assert ai.set_parameters([Parameter("landing", value="home")])[0].successful
    set_process_ros_arguments(parse_ros_args(["-p", "landing:=moon"]))
    with pytest.raises(InvalidParameterValueException, match="landing must be one of"):
        _ai(tmp_path)
