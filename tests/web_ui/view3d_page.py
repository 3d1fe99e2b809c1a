"""Driving the dashboard's 3D view as a user does (tabs, selects, buttons), reading back what it
draws through ``window.skydeck.view3d()`` (positions in the fixed frame, read from the scene)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from tests.web_ui.system import REPO

WAIT_MS = 20_000


def open_3d(page: Any) -> None:
    """Click the 3D tab and wait until the view has loaded and drawn a frame."""
    # After a (re)load, main.js wires the tabs and sets window.skydeck only once config.js's
    # top-level await is over, which can be after the load event: a click before is lost.
    page.wait_for_function("window.skydeck !== undefined", timeout=WAIT_MS)
    page.click("[data-tab=view3d]")
    page.wait_for_function(
        "(() => { const v = window.skydeck && window.skydeck.view3d(); return v && v.shown && v.frameStats.rendered > 0; })()",
        timeout=WAIT_MS,
    )


def view(page: Any) -> dict[str, Any]:
    return page.evaluate("window.skydeck.view3d()")  # type: ignore[no-any-return]


def wait_view(page: Any, condition: str, timeout_ms: int = WAIT_MS) -> dict[str, Any]:
    """Wait until ``condition`` (JS, with ``v`` the view's snapshot) holds; returns that snapshot
    (not a later one, in which the condition may no longer hold)."""
    return page.wait_for_function(  # type: ignore[no-any-return]
        f"(() => {{ const v = window.skydeck && window.skydeck.view3d(); return !!v && ({condition}) ? v : null; }})()",
        timeout=timeout_ms,
    ).json_value()


def wait_display(
    page: Any, topic: str, condition: str, timeout_ms: int = WAIT_MS
) -> dict[str, Any]:
    """Wait until the display of ``topic`` satisfies ``condition`` (JS, with ``d`` the display and
    ``v`` the view's snapshot); returns the display as it was when the condition held."""
    return wait_view_with_display(page, topic, condition, timeout_ms)[1]


def wait_view_with_display(
    page: Any, topic: str, condition: str, timeout_ms: int = WAIT_MS
) -> tuple[dict[str, Any], dict[str, Any]]:
    """As :func:`wait_display`, with the view's snapshot the display was taken from (to compare
    the display with the world of the same moment)."""
    v = wait_view(
        page,
        "(() => { const d = v.displays.find((x) => x.topic === "
        + json.dumps(topic)
        + f"); return !!d && ({condition}); }})()",
        timeout_ms,
    )
    return v, next(d for d in v["displays"] if d["topic"] == topic)


def add_by_topic(page: Any, topic: str, color: str | None = None) -> None:
    """Pick ``topic`` in the "add by topic" list (waiting for it to be offered) and add it."""
    page.wait_for_selector(
        f"#view3d-add-select option[value={json.dumps(topic)}]", state="attached", timeout=WAIT_MS
    )
    page.select_option("#view3d-add-select", topic)
    if color:
        page.fill("#view3d-add-color", color)
    page.click("#view3d-add")
    page.wait_for_selector(f"#view3d-displays li[data-topic={json.dumps(topic)}]", timeout=WAIT_MS)


def row(page: Any, topic: str) -> Any:
    return page.locator(f"#view3d-displays li[data-topic={json.dumps(topic)}]")


def status_texts(d: dict[str, Any]) -> list[str]:
    """A display's status lines, as the panel shows them ("Key: text")."""
    return [f"{e['key']}: {e['text']}" for e in d["status"]["entries"]]


def follow_and_zoom(page: Any, notches: int, followed: str) -> None:
    """Reset the view, follow the robot (or drone: Follow brings the camera close to it), zoom in
    ``notches`` wheel steps (negative: out); wait until the view is centred on ``followed`` (JS:
    its position in the snapshot ``v``)."""
    page.click("#view3d-reset")
    page.click("#view3d-follow")
    box = page.locator("#view3d-canvas").bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    for _ in range(abs(notches)):
        page.mouse.wheel(0, -250 if notches > 0 else 250)
    wait_view(
        page,
        f"v.camera.follow && Math.hypot(v.camera.target[0] - {followed}[0], v.camera.target[1] - {followed}[1]) < 0.2",
    )


def screenshot_path(name: str, tmp_path: Path) -> Path:
    """docs/img/NAME when SKYDECK_UPDATE_SCREENSHOTS=1 (the docs' pictures are refreshed only on
    request, so a test run never edits tracked files), else a file in ``tmp_path``."""
    return (
        REPO / "docs" / "img" / name
        if os.environ.get("SKYDECK_UPDATE_SCREENSHOTS") == "1"
        else tmp_path / name
    )
