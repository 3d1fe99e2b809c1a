"""What the CLI prints of a refusal, whatever shape of body it came with (unit level)."""

from __future__ import annotations

import httpx
import pytest

from services.cli.core_client import error_detail


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
    assert error_detail(httpx.Response(422, json=body)) == expected


def test_detail_of_a_body_that_is_not_json() -> None:
    assert error_detail(httpx.Response(502, text="Bad Gateway\n")) == "Bad Gateway"
