"""What the Windows tab sends for a viewer's keys and mouse (web_ui/static/js/window_input.js),
run in Chromium: key codes as cv2.waitKeyEx gives them on Linux, OpenCV's mouse events and
flags, the wheel's delta in the flags' high bits, and the input queue that keeps order and folds
only moves in a row."""

from __future__ import annotations

import json
from collections.abc import Iterator

import pytest

from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import started

pytestmark = [pytest.mark.browser, pytest.mark.timeout(60)]


@pytest.fixture(scope="module")
def page(browser: object) -> Iterator[object]:
    with started() as system, open_dashboard(browser, system.url, "window.skydeck !== undefined") as (page, recorder):
        yield page
        assert recorder.errors == []


def _run(page: object, body: str) -> object:
    return page.evaluate(f"async () => {{ const m = await import('/static/js/window_input.js'); {body} }}")  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    ("key", "code"),
    [
        ({"key": "q"}, ord("q")), ({"key": "Q", "shiftKey": True}, ord("Q")), ({"key": " "}, 32),
        ({"key": "é"}, 0xE9), ({"key": "Enter"}, 13), ({"key": "Escape"}, 27), ({"key": "Backspace"}, 8),
        ({"key": "Tab"}, 9), ({"key": "ArrowLeft"}, 65361), ({"key": "ArrowUp"}, 65362),
        ({"key": "ArrowRight"}, 65363), ({"key": "ArrowDown"}, 65364), ({"key": "Delete"}, 0xFFFF),
        ({"key": "F1"}, 0xFFBE), ({"key": "F12"}, 0xFFC9),
        ({"key": "Shift"}, None), ({"key": "Dead"}, None), ({"key": "c", "ctrlKey": True}, None), ({"key": "v", "metaKey": True}, None),
    ],
)  # fmt: skip
def test_keys_are_the_codes_waitkeyex_returns_on_linux(page: object, key: dict, code: int | None) -> None:
    assert _run(page, f"return m.keyCode({json.dumps(key)});") == code


def test_mouse_buttons_wheel_and_flags_are_opencvs(page: object) -> None:
    assert _run(page, "return [0, 2, 1].map(b => [m.buttonEvent(b, 'down'), m.buttonEvent(b, 'up'), m.buttonEvent(b, 'double')]);") == [
        [1, 4, 7], [2, 5, 8], [3, 6, 9],  # EVENT_L/R/MBUTTONDOWN, ...UP, ...DBLCLK
    ]  # fmt: skip
    assert _run(page, "return m.buttonEvent(3, 'down');") is None  # a back button: no OpenCV event
    assert _run(page, "return m.mouseFlags({buttons: 1, ctrlKey: true, shiftKey: false, altKey: true});") == 1 | 8 | 32
    assert _run(page, "return m.mouseFlags({buttons: 6});") == 2 | 4  # right and middle held
    assert _run(page, "return m.wheelEvent({deltaX: 0, deltaY: -100, buttons: 0});") == [10, 120 << 16]  # away: +120
    assert _run(page, "return m.wheelEvent({deltaX: 0, deltaY: 40, buttons: 0, shiftKey: true});") == [10, (-120 << 16) | 16]
    assert _run(page, "return m.wheelEvent({deltaX: 30, deltaY: 0, buttons: 0});") == [11, 120 << 16]


def test_the_queue_keeps_order_and_folds_only_moves_in_a_row(page: object) -> None:
    sent = _run(
        page,
        """
        const queue = new m.InputQueue('/nobody/opencv/input');
        queue.busy = true;  // a call in flight: what follows waits
        const move = (x) => queue.send({kind: 'mouse', event: 0, x}, {fold: 'move:w'});
        move(1); move(2); queue.send({kind: 'mouse', event: 1, x: 2}); move(3); move(4);
        queue.send({kind: 'trackbar', value: 5}, {fold: 't'}); queue.send({kind: 'trackbar', value: 6}, {fold: 't'});
        return queue.pending.map(p => p.request.kind === 'trackbar' ? `t${p.request.value}` : `${p.request.event}@${p.request.x}`);
        """,
    )
    assert sent == ["0@2", "1@2", "0@4", "t6"]
