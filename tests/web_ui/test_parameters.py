"""The dashboard's Parameters tab against the real system (core, sim, control), in Chromium: pick
a node, see its parameters, set one, see a refusal's reason, and follow a change made elsewhere."""

from __future__ import annotations

import json
import urllib.request

import pytest

from tests.web_ui.system import System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]


def _set_parameters(system: System, node: str, parameters: list[dict[str, object]]) -> dict[str, object]:
    request = urllib.request.Request(
        f"{system.url}{node}/set_parameters",
        data=json.dumps({"parameters": parameters}).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=10) as reply:
        return json.loads(reply.read())  # type: ignore[no-any-return]


def _rows(page) -> dict[str, dict[str, object]]:  # type: ignore[no-untyped-def]
    return {row["name"]: row for row in page.evaluate("window.skydeck.parameters.rows")}


def _pick(page, node: str) -> None:  # type: ignore[no-untyped-def]
    page.click("[data-tab=parameters]")
    page.wait_for_function(f"[...document.querySelectorAll('#param-node option')].some(o => o.value === '{node}')", timeout=10_000)
    page.select_option("#param-node", node)
    page.locator('#param-list tr[data-param="use_sim_time"]').wait_for(timeout=10_000)


def test_a_nodes_parameters_are_listed_with_types_and_values(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, recorder = dashboard
    _pick(page, "/sim")
    rows = _rows(page)
    assert rows["seed"]["value"] == 1 and rows["seed"]["readOnly"] is True
    assert rows["boxes"]["value"] == 8 and rows["use_sim_time"]["value"] is False
    seed_row = page.locator('#param-list tr[data-param="seed"]')
    assert "integer, read-only" in seed_row.inner_text()
    assert seed_row.locator("input").input_value() == "1"
    assert "random seed" in (seed_row.locator("td").first.get_attribute("title") or "")
    assert recorder.errors == []


def test_a_refusal_shows_the_nodes_reason_and_keeps_the_value(dashboard) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    _pick(page, "/sim")
    page.fill('#param-list input[data-param="seed"]', "7")
    page.press('#param-list input[data-param="seed"]', "Enter")
    page.wait_for_function("(window.skydeck.parameters.last || {}).kind === 'refused'", timeout=10_000)
    assert "seed refused: parameter 'seed' is read-only" in page.inner_text("#param-result")
    page.wait_for_function("document.querySelector('#param-list input[data-param=\"seed\"]').value === '1'", timeout=10_000)
    page.fill('#param-list input[data-param="use_sim_time"]', "maybe")
    page.press('#param-list input[data-param="use_sim_time"]', "Enter")
    page.wait_for_function("(window.skydeck.parameters.last || {}).message.includes('maybe')", timeout=10_000)
    assert "is of type boolean; got string 'maybe'" in page.inner_text("#param-result")


def test_a_change_is_set_and_one_made_elsewhere_is_followed(dashboard, system: System) -> None:  # type: ignore[no-untyped-def]
    page, _ = dashboard
    _pick(page, "/control")
    page.fill('#param-list input[data-param="use_sim_time"]', "true")
    page.press('#param-list input[data-param="use_sim_time"]', "Enter")
    page.wait_for_function("(window.skydeck.parameters.last || {}).kind === 'success'", timeout=10_000)
    assert page.inner_text("#param-result").startswith("✓ use_sim_time = true")
    page.wait_for_function(
        "window.skydeck.parameters.rows.find(r => r.name === 'use_sim_time').value === true", timeout=10_000
    )
    # Changed by someone else (the CLI, say): /parameter_events brings the new value to the page.
    result = _set_parameters(system, "/control", [{"name": "use_sim_time", "value": {"type": 1, "bool_value": False}}])
    assert result["results"][0]["successful"]  # type: ignore[index]
    page.wait_for_function(
        "document.querySelector('#param-list input[data-param=\"use_sim_time\"]').value === 'false'", timeout=10_000
    )
