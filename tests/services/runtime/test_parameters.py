"""A node's parameters on their own (no sockets): values and types, descriptors, overrides,
on-set callbacks, undeclared names, events."""

from __future__ import annotations

import pytest

from services.runtime.parameter import Parameter, parameter_value_to_python
from services.runtime.parameters import (
    InvalidParameterException,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    NodeParameters,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from shared_models.rcl_interfaces import (
    FloatingPointRange,
    IntegerRange,
    ParameterDescriptor,
    ParameterEvent,
    ParameterType,
    SetParametersResult,
)
from shared_models.rcl_interfaces import Parameter as ParameterMsg

T = Parameter.Type


# -- one value --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("value", "type_"),
    [
        (True, T.BOOL),
        (3, T.INTEGER),
        (0.5, T.DOUBLE),
        ("robot1", T.STRING),
        (b"\x00\x01", T.BYTE_ARRAY),
        ([True, False], T.BOOL_ARRAY),
        ([1, 2], T.INTEGER_ARRAY),
        ([1.0, 2.5], T.DOUBLE_ARRAY),
        ([1, 2.5], T.DOUBLE_ARRAY),
        (["a", "b"], T.STRING_ARRAY),
        (None, T.NOT_SET),
    ],
)
def test_a_value_has_its_ros_type_and_survives_the_message(value, type_) -> None:
    parameter = Parameter("p", value=value)
    assert parameter.type_ is type_ and parameter.type_ == getattr(ParameterType, f"PARAMETER_{type_.name}")
    again = Parameter.from_parameter_msg(ParameterMsg.model_validate_json(parameter.to_parameter_msg().model_dump_json()))
    assert again == parameter
    assert parameter_value_to_python(parameter.get_parameter_value()) == parameter.value


def test_rclpy_constructors_and_their_errors() -> None:
    assert Parameter("speed", Parameter.Type.DOUBLE, 0.5).value == 0.5
    assert Parameter("speed", value=0.5).type_ is T.DOUBLE
    with pytest.raises(ValueError, match="do not agree"):
        Parameter("speed", Parameter.Type.DOUBLE, "fast")
    for bad in ({"a": 1}, [1, "a"], object()):
        with pytest.raises(TypeError, match="not a parameter value"):
            Parameter("x", value=bad)
    with pytest.raises(ValueError, match="not finite"):
        Parameter("x", value=float("nan"))
    with pytest.raises(ValueError, match="JSON carries exactly"):
        Parameter("x", value=2**53)


# -- declaring --------------------------------------------------------------------------------


def _parameters(**kwargs) -> tuple[NodeParameters, list[ParameterEvent]]:
    events: list[ParameterEvent] = []
    return NodeParameters("/n", on_event=events.append, **kwargs), events


def test_declare_takes_the_override_instead_of_the_default() -> None:
    params, _ = _parameters(overrides={"speed": 1.5, "name": "r2"})
    assert params.declare("speed", 0.3).value == 1.5
    assert params.declare("name", "robot1", ignore_override=True).value == "robot1"
    assert params.declare("gain", 2.0).value == 2.0
    with pytest.raises(ParameterAlreadyDeclaredException):
        params.declare("gain", 1.0)
    with pytest.raises(InvalidParameterException, match="not a parameter name"):
        params.declare("bad name", 1)


def test_an_override_of_the_wrong_type_is_refused_naming_the_parameter() -> None:
    params, _ = _parameters(overrides={"speed": "fast"})
    with pytest.raises(InvalidParameterTypeException) as raised:
        params.declare("speed", 0.3)
    message = str(raised.value)
    assert "'speed'" in message and "double" in message and "'fast'" in message and "override" in message
    assert not params.has("speed")  # nothing half-declared


def test_an_integer_is_taken_for_a_double_but_not_the_other_way() -> None:
    params, _ = _parameters(overrides={"speed": 2})
    assert params.declare("speed", 0.3).value == 2.0 and params.get("speed").type_ is T.DOUBLE
    params.declare("count", 3)
    [result] = params.set([Parameter("count", value=2.5)])
    assert not result.successful and "integer" in result.reason


def test_typed_without_value_and_dynamically_typed() -> None:
    params, _ = _parameters()
    params.declare("typed", Parameter.Type.DOUBLE)
    with pytest.raises(ParameterUninitializedException, match="no value yet"):
        params.get("typed")
    assert params.set([Parameter("typed", value=1.0)])[0].successful
    params.declare("anything")
    assert params.get("anything").type_ is T.NOT_SET
    assert params.set([Parameter("anything", value="text")])[0].successful
    assert params.set([Parameter("anything", value=3)])[0].successful


def test_an_empty_list_takes_the_type_of_the_first_list_it_is_given() -> None:
    params, _ = _parameters(overrides={"names": ["a", "b"]})
    assert params.declare("names", []).value == ["a", "b"]
    [refused] = params.set([Parameter("names", value=[1])])
    assert not refused.successful and "string array" in refused.reason
    params.declare("later", [])
    assert params.set([Parameter("later", value=[1, 2])])[0].successful
    assert params.describe("later").type == T.INTEGER_ARRAY
    assert params.set([Parameter("later", value=[])])[0].successful  # empty again: still integers
    assert not params.set([Parameter("later", value=["x"])])[0].successful


# -- setting ----------------------------------------------------------------------------------


def test_type_read_only_and_ranges_are_checked() -> None:
    params, _ = _parameters()
    params.declare("frozen", 1, ParameterDescriptor(read_only=True))
    speed_range = FloatingPointRange(from_value=0.0, to_value=2.0, step=0.5)
    params.declare("speed", 0.5, ParameterDescriptor(floating_point_range=[speed_range]))
    params.declare("count", 4, ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=10, step=2)]))
    cases = {
        ("frozen", 2): "read-only",
        ("speed", "fast"): "of type double",
        ("speed", 2.5): "outside its range",
        ("speed", 0.7): "not on a step",
        ("count", 5): "not on a step",
        ("count", -2): "outside its range",
    }
    for (name, value), reason in cases.items():
        [result] = params.set([Parameter(name, value=value)])
        assert not result.successful and reason in result.reason, (name, value, result)
    assert [r.successful for r in params.set([Parameter("speed", value=1.5), Parameter("count", value=10)])] == [True, True]
    assert params.get("speed").value == 1.5 and params.get("frozen").value == 1


def test_an_on_set_callback_may_refuse_with_a_reason_and_the_latest_is_asked_first() -> None:
    params, events = _parameters()
    params.declare("speed", 0.5)
    asked: list[str] = []

    def at_most_one(parameters: list[Parameter]) -> SetParametersResult:
        asked.append("at_most_one")
        too_fast = [p for p in parameters if p.name == "speed" and p.value > 1.0]
        return SetParametersResult(successful=not too_fast, reason="speed is at most 1 m/s" if too_fast else "")

    def anything(parameters: list[Parameter]) -> SetParametersResult:
        asked.append("anything")
        return SetParametersResult(successful=True)

    params.on_set_callbacks.extend([anything, at_most_one])  # asked in this order
    events.clear()
    [result] = params.set([Parameter("speed", value=3.0)])
    assert result == SetParametersResult(successful=False, reason="speed is at most 1 m/s")
    assert asked == ["anything", "at_most_one"] and params.get("speed").value == 0.5 and not events
    params.on_set_callbacks.remove(at_most_one)
    assert params.set([Parameter("speed", value=3.0)])[0].successful


def test_atomic_sets_change_all_or_nothing() -> None:
    params, _ = _parameters()
    params.declare("a", 1)
    params.declare("b", 2, ParameterDescriptor(read_only=True))
    result = params.set_atomically([Parameter("a", value=10), Parameter("b", value=20)])
    assert not result.successful and "read-only" in result.reason
    assert params.get("a").value == 1


def test_a_callback_returning_something_else_is_a_type_error_and_its_exception_propagates() -> None:
    params, _ = _parameters()
    params.declare("a", 1)
    params.on_set_callbacks.append(lambda parameters: True)  # type: ignore[arg-type, return-value]
    with pytest.raises(TypeError, match="expected SetParametersResult"):
        params.set([Parameter("a", value=2)])
    with pytest.raises(TypeError):
        params.declare("b", 1)
    assert not params.has("b") and params.get("a").value == 1  # nothing half-declared or half-set


def test_undeclared_names_are_refused_unless_the_node_allows_them() -> None:
    params, _ = _parameters()
    with pytest.raises(ParameterNotDeclaredException, match="'ghost'"):
        params.set([Parameter("ghost", value=1)])
    with pytest.raises(ParameterNotDeclaredException):
        params.get("ghost")
    open_params, events = _parameters(allow_undeclared_parameters=True)
    assert open_params.get("ghost").type_ is T.NOT_SET
    assert open_params.set([Parameter("ghost", value=1)])[0].successful
    assert open_params.set([Parameter("ghost", value="now a string")])[0].successful  # dynamically typed
    assert [p.name for p in events[0].new_parameters] == ["ghost"] and events[1].changed_parameters
    assert open_params.set([Parameter("ghost")])[0].successful  # NOT_SET deletes it
    assert not open_params.has("ghost") and events[-1].deleted_parameters[0].name == "ghost"


def test_undeclare_and_read_only() -> None:
    params, events = _parameters()
    params.declare("a", 1)
    params.declare("b", 2, ParameterDescriptor(read_only=True))
    params.undeclare("a")
    assert not params.has("a") and events[-1].deleted_parameters[0].name == "a"
    with pytest.raises(ParameterImmutableException):
        params.undeclare("b")
    with pytest.raises(ParameterNotDeclaredException):
        params.undeclare("a")


def test_events_name_new_and_changed_parameters() -> None:
    params, events = _parameters()
    params.declare("speed", 0.5)
    params.set([Parameter("speed", value=0.7)])
    assert events[0].node == "/n" and [p.name for p in events[0].new_parameters] == ["speed"]
    assert events[1].changed_parameters[0].value.double_value == 0.7 and not events[1].new_parameters


def test_post_set_callbacks_see_accepted_changes_only() -> None:
    params, _ = _parameters()
    seen: list[list[str]] = []
    params.post_set_callbacks.append(lambda parameters: seen.append([p.name for p in parameters]))
    params.declare("a", 1)
    params.set([Parameter("a", value="no")])
    params.set([Parameter("a", value=2)])
    assert seen == [["a"], ["a"]]


def test_list_by_prefix_and_depth() -> None:
    params, _ = _parameters()
    for name in ("use_sim_time", "gains.p", "gains.i", "gains.limits.max"):
        params.declare(name, 1)
    assert params.list_names().names == ["gains.i", "gains.limits.max", "gains.p", "use_sim_time"]
    assert params.list_names().prefixes == ["gains", "gains.limits"]
    assert params.list_names(depth=1).names == ["use_sim_time"]
    assert params.list_names(["gains"], depth=1).names == ["gains.i", "gains.p"]
    assert params.list_names(["gains"]).names == ["gains.i", "gains.limits.max", "gains.p"]


def test_a_refusal_at_declare_time_raises() -> None:
    params, _ = _parameters(overrides={"speed": 5.0})
    with pytest.raises(InvalidParameterValueException, match="outside its range"):
        params.declare("speed", 1.0, ParameterDescriptor(floating_point_range=[FloatingPointRange(from_value=0, to_value=2)]))
