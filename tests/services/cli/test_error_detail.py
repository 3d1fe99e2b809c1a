"""What the CLI prints of a refusal, whatever shape of body it came with, and of a request it
cannot send (unit level)."""

from __future__ import annotations

import json

import pytest

from services.cli.core_client import error_detail
from services.cli.main import main
from services.runtime.http_client import HttpReply


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        ({"detail": "no service /x: see `skydeck service list`"}, "no service /x: see `skydeck service list`"),
        ({"detail": [{"loc": ["body", "x"], "msg": "Input should be a valid number"}]}, "x: Input should be a valid number"),
        ({"detail": [{"loc": ["body"], "msg": "Field required"}]}, "body: Field required"),
        (["not", "an", "object"], "['not', 'an', 'object']"),
        ("just text", "just text"),
    ],
)
def test_detail_of_any_json_body(body: object, expected: str) -> None:
    assert error_detail(HttpReply(422, {"content-type": "application/json"}, json.dumps(body).encode())) == expected


def test_detail_of_a_body_that_is_not_json() -> None:
    assert error_detail(HttpReply(502, {"content-type": "text/plain"}, b"Bad Gateway\n")) == "Bad Gateway"


@pytest.mark.parametrize("data", ["{x: .nan}", "{when: 2024-01-01}"])
def test_a_request_json_cannot_carry_is_one_line_before_anything_is_sent(
    data: str, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SKYDECK_CORE_URL", "http://127.0.0.1:9")  # nothing listens: nothing may be sent
    assert main(["service", "call", "/x", data]) == 1
    err = capsys.readouterr().err
    assert err.startswith("skydeck: error: the request cannot be sent as JSON") and err.count("\n") == 1
