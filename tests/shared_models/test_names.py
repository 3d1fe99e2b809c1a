"""ROS names: resolving, validating and refusing the core's own routes."""

from __future__ import annotations

import pytest

from shared_models import RESERVED_PREFIXES, InvalidNameError, resolve_name, resolve_node_name
from shared_models.names import check_not_reserved


@pytest.mark.parametrize(
    ("name", "namespace", "expected"),
    [
        ("my_point", "/", "/my_point"),
        ("perception/boxes", "/", "/perception/boxes"),
        ("/drone/pose", "/", "/drone/pose"),
        ("boxes", "/perception", "/perception/boxes"),
        ("boxes", "/perception/", "/perception/boxes"),
        ("/drone/pose", "/perception", "/drone/pose"),
        ("/a1/B_2", "/", "/a1/B_2"),
        ("/apiary", "/", "/apiary"),
        ("/static_map", "/", "/static_map"),
        ("/drone/api", "/", "/drone/api"),
        ("/fibonacci/_action/send_goal", "/", "/fibonacci/_action/send_goal"),  # ROS 2's hidden names
        ("_action/status", "/fibonacci", "/fibonacci/_action/status"),
    ],
)
def test_valid_names(name: str, namespace: str, expected: str) -> None:
    assert resolve_name(name, namespace) == expected


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("/drone//pose", "invalid name '/drone//pose': empty token at position 7"),
        (
            "/drone/po se",
            "invalid name '/drone/po se': ' ' at position 9 is not allowed "
            "(letters, digits, _ and / only)",
        ),
        ("/drone/", "invalid name '/drone/': trailing '/' at position 6"),
        ("//drone", "invalid name '//drone': empty token at position 1"),
        (
            "/1drone",
            "invalid name '/1drone': token '1drone' at position 1 must start with a letter or '_'",
        ),
        ("/drone/9pose", "token '9pose' at position 7 must start with a letter"),
        ("~/private", "'~' at position 0 is not allowed"),
        ("/drone.pose", "'.' at position 6 is not allowed"),
        ("/drone/pösé", "'ö' at position 8 is not allowed"),
        ("", "invalid name '': a name needs at least one token"),
        ("/", "invalid name '/': a name needs at least one token"),
    ],
)
def test_invalid_names_say_what_and_where(name: str, message: str) -> None:
    with pytest.raises(InvalidNameError) as caught:
        resolve_name(name)
    assert message in str(caught.value)
    assert caught.value.name == name
    assert isinstance(caught.value, ValueError)


def test_bad_namespace_is_reported() -> None:
    with pytest.raises(InvalidNameError, match="must be absolute"):
        resolve_name("boxes", "perception")
    with pytest.raises(InvalidNameError, match="empty token"):
        resolve_name("boxes", "/a//b")


@pytest.mark.parametrize("prefix", RESERVED_PREFIXES)
def test_reserved_prefixes_are_refused(prefix: str) -> None:
    with pytest.raises(InvalidNameError, match="reserved"):
        check_not_reserved(prefix)
    with pytest.raises(InvalidNameError, match="reserved"):
        check_not_reserved(prefix + "/x")
    assert check_not_reserved(prefix + "x") == prefix + "x"


def test_resolve_name_applies_the_reserved_check() -> None:
    assert RESERVED_PREFIXES == ("/api", "/docs", "/redoc", "/openapi.json", "/static", "/health", "/rosbridge")
    for name in ("/api", "/api/graph", "api/graph", "/docs", "/health/live", "static", "/rosbridge"):
        with pytest.raises(InvalidNameError, match="reserved for the core's own routes"):
            resolve_name(name)
    with pytest.raises(InvalidNameError, match="reserved"):
        resolve_name("graph", "/api")


def test_node_names() -> None:
    assert resolve_node_name("send_message_node") == "/send_message_node"
    assert resolve_node_name("/talker") == "/talker"
    with pytest.raises(InvalidNameError, match="single token"):
        resolve_node_name("drone/control")
    with pytest.raises(InvalidNameError, match="needs one token"):
        resolve_node_name("")
    with pytest.raises(InvalidNameError, match="must start with a letter"):
        resolve_node_name("9lives")
    with pytest.raises(InvalidNameError, match="'-' at position 4"):
        resolve_node_name("send-message")
