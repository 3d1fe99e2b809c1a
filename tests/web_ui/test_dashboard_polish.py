"""The dashboard's small things, measured in Chromium against the real system (core, sim,
control): names and types never cut mid-word, legend swatches beside their labels, the 3D
topic select showing whole names, the graph readable without Expand, and the /rosout console
showing what was said before the page opened."""

from __future__ import annotations

import json
import time
import urllib.request

import pytest

from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import System

pytestmark = [pytest.mark.browser, pytest.mark.e2e, pytest.mark.slow, pytest.mark.timeout(120)]

READY = "window.skydeck && window.skydeck.pose !== null"
VIEWPORTS = [(1440, 900), (1280, 800)]

# Where a cell's text wraps: the characters that begin a new line, each with the one before it.
LINE_BREAKS_JS = """(cell) => {
  const text = cell.firstChild;
  if (!text || text.nodeType !== Node.TEXT_NODE) return [];
  const range = document.createRange();
  const breaks = [];
  let top = null;
  for (let i = 0; i < text.length; i++) {
    range.setStart(text, i);
    range.setEnd(text, i + 1);
    const rects = [...range.getClientRects()].filter((r) => r.width > 0);
    if (!rects.length) continue;
    if (top !== null && rects[0].top > top + 2) breaks.push([text.data[i - 1], text.data[i]]);
    top = rects[0].top;
  }
  return breaks;
}"""


@pytest.mark.parametrize(("width", "height"), VIEWPORTS)
def test_types_and_node_names_wrap_between_words_only(browser, system: System, width: int, height: int) -> None:  # type: ignore[no-untyped-def]
    with open_dashboard(browser, system.url, READY) as (page, _):
        page.set_viewport_size({"width": width, "height": height})
        page.wait_for_function("document.querySelectorAll('#topic-list td.type').length >= 5", timeout=10_000)
        cells = page.locator("#topic-list td.type, #service-list td.type, #topic-list td.flow")
        assert cells.count() >= 10
        wrapped = 0
        for index in range(cells.count()):
            cell = cells.nth(index)
            breaks = cell.evaluate(LINE_BREAKS_JS)
            wrapped += bool(breaks)
            for before, after in breaks:  # after the slash's zero-width space, or at a space
                assert before in ("\u200b", " ") or after == " ", (cell.inner_text(), before, after)
        assert wrapped, "no cell wrapped: the test measured nothing"


def test_each_legend_swatch_sits_before_its_label(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    with open_dashboard(browser, system.url, READY) as (page, _):
        items = page.evaluate(
            """() => [...document.querySelectorAll('#map-legend span')]
                .filter((item) => item.querySelector('i') && item.offsetParent !== null)
                .map((item) => {
                  const swatch = item.querySelector('i').getBoundingClientRect();
                  const range = document.createRange();
                  range.selectNodeContents(item.lastChild);
                  const label = range.getBoundingClientRect();
                  return { text: item.textContent, swatch: [swatch.left, swatch.right, swatch.top, swatch.bottom],
                           label: [label.left, label.right, label.top, label.bottom] };
                })"""
        )
    assert [item["text"] for item in items] == ["drone", "box", "visited", "target / tour", "setpoint"]
    for before, item in zip([None, *items], items, strict=False):
        swatch_left, swatch_right, swatch_top, swatch_bottom = item["swatch"]
        label_left, _, label_top, label_bottom = item["label"]
        assert swatch_right + 2 <= label_left, item  # a gap between swatch and label
        assert label_top <= (swatch_top + swatch_bottom) / 2 <= label_bottom, item  # on its line
        if before is not None and before["label"][2] == label_top:  # the previous item on that line
            assert before["label"][1] + 6 <= swatch_left, (before, item)


def test_the_3d_topic_select_shows_whole_names(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    with open_dashboard(browser, system.url, READY) as (page, _):
        page.click("[data-tab=view3d]")
        page.wait_for_function(
            "[...document.querySelectorAll('#view3d-add-select option')].some(o => o.value === '/drone/pose')", timeout=20_000
        )
        fits = page.evaluate(
            """() => {
              const select = document.getElementById('view3d-add-select');
              const style = getComputedStyle(select);
              const context = document.createElement('canvas').getContext('2d');
              context.font = `${style.fontSize} ${style.fontFamily}`;
              const room = select.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight) - 20;
              return [...select.options].map((o) => [o.text, context.measureText(o.text).width, room]);
            }"""
        )
    assert any(text.startswith("/drone/pose") for text, _, _ in fits)
    for text, needed, room in fits:
        assert needed <= room, f"{text!r} needs {needed:.0f} px, the select shows {room:.0f}"


def test_the_graph_is_readable_without_expand(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    measure = """() => {
      const svg = document.querySelector('#graph-diagram svg');
      const box = document.getElementById('graph-diagram');
      const label = svg.querySelector('g.vertex text').getBoundingClientRect();
      return { scale: svg.getBoundingClientRect().width / svg.viewBox.baseVal.width,
               labelPx: label.height, overflowX: box.scrollWidth - box.clientWidth,
               orientation: svg.dataset.orientation,
               names: [...svg.querySelectorAll('g.vertex')].map((g) => g.dataset.name) };
    }"""
    with open_dashboard(browser, system.url, READY) as (page, _):
        page.click("[data-tab=graph]")
        page.locator('#graph-diagram g[data-name="/control"]').wait_for(timeout=10_000)
        panel = page.evaluate(measure)
        # at full size in the panel, top to bottom, with nothing to scroll sideways
        assert panel["scale"] >= 0.99 and panel["labelPx"] >= 11 and panel["overflowX"] <= 1, panel
        assert panel["orientation"] == "rows"
        assert {"/sim", "/control", "/drone/pose", "/drone/setpoint"} <= set(panel["names"])
        assert "/skydeck_core" not in panel["names"] and "/rosout" not in panel["names"]  # debug: hidden
        page.click("#graph-expand")
        page.wait_for_function("document.querySelector('#graph-diagram svg').dataset.orientation === 'columns'", timeout=5_000)
        expanded = page.evaluate(measure)
        assert expanded["scale"] >= 0.8 and expanded["overflowX"] <= 1, expanded  # rqt_graph's columns
        page.check("#graph-show-debug")
        page.locator('#graph-diagram g[data-name="/skydeck_core"]').wait_for(timeout=5_000)


def _latest_rosout(system: System) -> list[dict]:  # type: ignore[type-arg]
    with urllib.request.urlopen(system.url + "/api/rosout?limit=200", timeout=5) as reply:
        return json.loads(reply.read())  # type: ignore[no-any-return]


def test_the_console_shows_what_was_said_before_the_page_opened(browser, system: System) -> None:  # type: ignore[no-untyped-def]
    request = urllib.request.Request(
        system.url + "/control/take_off", data=b"{}", headers={"Content-Type": "application/json"}, method="POST"
    )
    with urllib.request.urlopen(request, timeout=10):
        pass
    deadline = time.monotonic() + 20
    while not any(line["name"] == "/control" for line in _latest_rosout(system)):
        assert time.monotonic() < deadline, "control said nothing on /rosout"
        time.sleep(0.1)
    said = [line["msg"] for line in _latest_rosout(system) if line["name"] == "/control"]
    with open_dashboard(browser, system.url, READY) as (page, _):
        for _reload in range(2):  # at open, and after a reload
            page.wait_for_function(
                "(said) => said.every((m) => window.skydeck.log.some((e) => e.name === '/control' && e.msg === m))",
                arg=said, timeout=10_000,
            )  # fmt: skip
            shown = page.evaluate("window.skydeck.log.filter((e) => e.name === '/control').map((e) => e.msg)")
            assert shown[: len(said)] == said  # once each, oldest first
            assert page.locator("#log .log-entry").count() >= len(said)
            page.reload()
            page.wait_for_function(READY, timeout=20_000)
