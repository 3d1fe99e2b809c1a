"""OpenCV's HighGUI served by Skydeck (services/ros/highgui), in this process against a recording
host: what imshow keeps and when images go out, waitKey's keys and waits, trackbars and mouse
callbacks run in the thread that calls waitKey, the viewers' input checked, and every argument
error a cv2.error that says what was wrong. The real edge (topics, the input service, the
dashboard) is tests/ros/test_highgui_node.py and tests/web_ui/test_opencv_windows.py."""

from __future__ import annotations

import re
import threading
import time
import types
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

cv2 = pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")

from services.ros.highgui import install, serves_windows  # noqa: E402
from services.ros.highgui.display import displayable  # noqa: E402
from services.ros.highgui.functions import HighGuiFunctions  # noqa: E402
from services.ros.highgui.host import window_token  # noqa: E402
from services.ros.highgui.windows import HighGui, InputHandler  # noqa: E402
from shared_models.skydeck_opencv import WindowInputRequest, Windows  # noqa: E402

Input = WindowInputRequest


class RecordingHost:
    """A host that records what the windows send; ``watching`` says who reads which topic."""

    def __init__(self, take_input: InputHandler) -> None:
        self.take_input = take_input
        self.images: list[tuple[str, bytes]] = []
        self.descriptions: list[Windows] = []
        self.watching: set[str] = set()

    def add_window(self, name: str) -> str:
        return f"/test/opencv/{window_token(name, set())}"

    def watched(self, topic: str) -> bool:
        return topic in self.watching

    def publish_image(self, topic: str, jpeg: bytes) -> None:
        self.images.append((topic, jpeg))

    def publish_windows(self, windows: Windows) -> None:
        self.descriptions.append(windows)


class Gui:
    """The served functions over a recording host; ``cv2`` as a program sees it."""

    def __init__(self, *, max_rate_hz: float = 1000.0) -> None:
        self.hosts: list[RecordingHost] = []
        self.gui = HighGui(self._connect, max_rate_hz=max_rate_hz)
        self.cv2 = HighGuiFunctions(self.gui)

    def _connect(self, take_input: InputHandler) -> RecordingHost:
        self.hosts.append(RecordingHost(take_input))
        return self.hosts[-1]

    @property
    def host(self) -> RecordingHost:
        return self.hosts[0]

    def send(self, **fields: Any) -> Any:
        return self.host.take_input(Input(**fields))


@pytest.fixture
def gui() -> Gui:
    return Gui()


def _decoded(jpeg: bytes) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(jpeg, np.uint8), cv2.IMREAD_UNCHANGED)


# -- windows and images -----------------------------------------------------------------------


def test_imshow_keeps_a_copy_and_the_image_goes_out_in_waitkey_only_while_watched(gui: Gui) -> None:
    image = np.full((20, 30, 3), 50, np.uint8)
    gui.cv2.imshow("video window", image)
    assert len(gui.hosts) == 1 and gui.host.images == []  # imshow only keeps it
    image[:] = 250  # the program draws on its array after imshow: the window keeps what it showed
    assert gui.cv2.waitKey(1) == -1
    assert gui.host.images == []  # nobody watches: nothing encoded
    gui.host.watching.add("/test/opencv/video_window")
    gui.cv2.waitKey(1)
    [(topic, jpeg)] = gui.host.images
    assert topic == "/test/opencv/video_window"
    shown = _decoded(jpeg)
    assert shown.shape == (20, 30, 3) and abs(int(shown.mean()) - 50) <= 2
    gui.cv2.waitKey(1)
    assert len(gui.host.images) == 1  # the same image is not sent twice
    [description] = gui.host.descriptions[-1].windows
    assert (description.name, description.topic, description.width, description.height) == ("video window", "/test/opencv/video_window", 30, 20)


def test_images_go_out_at_most_at_the_rate() -> None:
    gui = Gui(max_rate_hz=1.0)
    gui.cv2.namedWindow("w")
    gui.host.watching.add("/test/opencv/w")
    for level in range(5):
        gui.cv2.imshow("w", np.full((4, 4), level * 10, np.uint8))
        gui.cv2.waitKey(1)
    assert len(gui.host.images) == 1  # one a second at most; the newest waits
    assert abs(int(_decoded(gui.host.images[0][1]).mean())) <= 2


def test_what_imshow_shows_follows_opencvs_rules() -> None:
    grey16 = np.full((2, 3), 0x8000, np.uint16)
    assert displayable("w", grey16).tolist() == [[128] * 3] * 2  # divided by 256
    ones = np.full((2, 2), 0.5, np.float32)
    assert displayable("w", ones).tolist() == [[128, 128], [128, 128]]  # times 255
    bgra = np.zeros((2, 2, 4), np.uint8)
    bgra[..., 2] = 200
    assert displayable("w", bgra).shape == (2, 2, 3) and displayable("w", bgra)[0, 0].tolist() == [0, 0, 200]
    assert displayable("w", np.zeros((2, 2, 1), np.uint8)).shape == (2, 2)
    assert displayable("w", cv2.UMat(np.ones((3, 3), np.uint8))).tolist() == [[1] * 3] * 3


@pytest.mark.parametrize(
    ("image", "says"),
    [
        (None, "the image is None (did cv2.imread fail"),
        ([[1, 2]], "must be a numpy array (or a cv2.UMat), not list"),
        (np.zeros((0, 4), np.uint8), "height x width"),
        (np.zeros((4,), np.uint8), "height x width"),
        (np.zeros((2, 2, 2), np.uint8), "2 channels cannot be shown"),
        (np.zeros((2, 2), np.int32), "int32 pixels cannot be shown"),
        (np.zeros((2, 2), bool), "bool pixels cannot be shown"),
    ],
)
def test_an_image_that_cannot_be_shown_is_a_cv2_error_that_says_why(gui: Gui, image: Any, says: str) -> None:
    with pytest.raises(cv2.error, match=f"cv2.imshow\\('w', ...\\): .*{says.replace('(', '.').replace(')', '.')}"):
        gui.cv2.imshow("w", image)
    assert gui.gui.names() == []  # nothing opened


def test_windows_open_close_and_are_described(gui: Gui) -> None:
    gui.cv2.namedWindow("a")
    gui.cv2.namedWindow("b", cv2.WINDOW_NORMAL)
    gui.cv2.namedWindow("a")  # again: nothing new
    assert [w.name for w in gui.host.descriptions[-1].windows] == ["a", "b"]
    assert gui.cv2.getWindowProperty("a", cv2.WND_PROP_VISIBLE) == 1.0
    assert gui.cv2.getWindowProperty("a", cv2.WND_PROP_AUTOSIZE) == 1.0
    assert gui.cv2.getWindowProperty("b", cv2.WND_PROP_AUTOSIZE) == 0.0
    gui.cv2.resizeWindow("b", 320, 240)
    gui.cv2.resizeWindow("a", (64, 48))
    gui.cv2.setWindowTitle("a", "Video")
    gui.cv2.moveWindow("a", 10, 20)
    gui.cv2.setWindowProperty("a", cv2.WND_PROP_FULLSCREEN, cv2.WINDOW_FULLSCREEN)
    a, b = gui.host.descriptions[-1].windows
    assert (a.title, a.display_width, a.display_height, b.display_width, b.display_height) == ("Video", 64, 48, 320, 240)
    assert gui.cv2.getWindowImageRect("b") == (0, 0, 320, 240)
    gui.cv2.destroyWindow("a")
    gui.cv2.destroyWindow("never opened")  # nothing, as in OpenCV
    assert [w.name for w in gui.host.descriptions[-1].windows] == ["b"]
    assert gui.cv2.getWindowProperty("a", cv2.WND_PROP_VISIBLE) == 0.0
    assert gui.cv2.getWindowProperty("a", cv2.WND_PROP_AUTOSIZE) == -1.0
    gui.cv2.destroyAllWindows()
    assert gui.host.descriptions[-1].windows == []
    assert gui.cv2.startWindowThread() == 0


# -- waitKey ------------------------------------------------------------------------------------


def test_waitkey_waits_its_delay_and_returns_minus_one(gui: Gui) -> None:
    gui.cv2.namedWindow("w")
    for delay_ms in (1, 30):
        started = time.monotonic()
        assert gui.cv2.waitKey(delay_ms) == -1
        assert time.monotonic() - started >= delay_ms / 1000  # paces a loop as on a desktop
    assert gui.cv2.pollKey() == -1


def test_keys_come_back_from_waitkey_in_order(gui: Gui) -> None:
    gui.cv2.namedWindow("w")
    for key in (ord("q"), 27, 0xFF51):  # q, Escape, the left arrow (GTK's code)
        assert gui.send(window="w", kind="key", key=key).success
    assert gui.cv2.waitKey(1) == ord("q")
    assert gui.cv2.waitKeyEx(1) == 27
    assert gui.cv2.waitKey(1) == 0x51  # waitKey keeps the low byte, as OpenCV's does
    assert gui.send(window="w", kind="key", key=0xFF53).success
    assert gui.cv2.pollKey() == 0xFF53
    assert gui.cv2.waitKey(1) == -1


def test_waitkey_zero_waits_for_a_key(gui: Gui) -> None:
    gui.cv2.namedWindow("w")
    returned: list[int] = []
    waiter = threading.Thread(target=lambda: returned.append(gui.cv2.waitKey(0)))
    waiter.start()
    waiter.join(0.2)
    assert waiter.is_alive()  # no key yet: still waiting
    gui.send(window="w", kind="key", key=ord("x"))
    waiter.join(5)
    assert returned == [ord("x")]


def test_a_watched_window_gets_its_image_during_a_long_wait(gui: Gui) -> None:
    gui.cv2.imshow("w", np.zeros((4, 4), np.uint8))
    returned: list[int] = []
    waiter = threading.Thread(target=lambda: returned.append(gui.cv2.waitKey(0)))  # imshow, then wait for a key
    waiter.start()
    gui.host.watching.add("/test/opencv/w")  # someone opens the panel while the program waits
    _until(lambda: len(gui.host.images) == 1)
    gui.send(window="w", kind="key", key=32)
    waiter.join(5)
    assert returned == [32]


# -- trackbars ------------------------------------------------------------------------------------


def test_a_trackbar_moved_by_a_viewer_calls_back_in_the_thread_that_calls_waitkey(gui: Gui) -> None:
    calls: list[tuple[int, str]] = []
    gui.cv2.namedWindow("mask")
    gui.cv2.createTrackbar("hue", "mask", 300, 179, lambda pos: calls.append((pos, threading.current_thread().name)))
    assert gui.cv2.getTrackbarPos("hue", "mask") == 179  # clamped to the range
    assert calls == []  # not called at creation, as in OpenCV
    assert gui.send(window="mask", kind="trackbar", trackbar="hue", value=20).success
    assert gui.cv2.getTrackbarPos("hue", "mask") == 179  # moved only when the window system runs
    loop = threading.Thread(target=lambda: gui.cv2.waitKey(1), name="vision loop")
    loop.start()
    loop.join(5)
    assert calls == [(20, "vision loop")]
    assert gui.cv2.getTrackbarPos("hue", "mask") == 20
    [window] = gui.host.descriptions[-1].windows
    assert [(t.name, t.value, t.minimum, t.maximum) for t in window.trackbars] == [("hue", 20, 0, 179)]


def test_set_trackbar_pos_calls_back_when_it_moves(gui: Gui) -> None:
    calls: list[int] = []
    gui.cv2.namedWindow("w")
    gui.cv2.createTrackbar("t", "w", 5, 10, calls.append)
    gui.cv2.setTrackbarPos("t", "w", 7)
    gui.cv2.setTrackbarPos("t", "w", 7)  # not moved: no call
    gui.cv2.setTrackbarPos("t", "w", 99)  # clamped
    assert calls == [7, 10]
    gui.cv2.setTrackbarMin("t", "w", 2)
    gui.cv2.setTrackbarMax("t", "w", 8)
    assert gui.cv2.getTrackbarPos("t", "w") == 8  # clamped into the new range
    [window] = gui.host.descriptions[-1].windows
    assert [(t.value, t.minimum, t.maximum) for t in window.trackbars] == [(8, 2, 8)]
    gui.cv2.createTrackbar("t", "w", 1, 3, calls.append)  # the same name again replaces it
    assert gui.cv2.getTrackbarPos("t", "w") == 1


def test_a_callback_that_raises_is_printed_and_the_loop_goes_on(gui: Gui, capsys: pytest.CaptureFixture[str]) -> None:
    def broken(pos: int) -> None:
        raise ValueError(f"bad position {pos}")

    gui.cv2.namedWindow("w")
    gui.cv2.createTrackbar("t", "w", 0, 10, broken)
    gui.send(window="w", kind="trackbar", trackbar="t", value=3)
    gui.send(window="w", kind="key", key=ord("k"))
    assert gui.cv2.waitKey(1) == ord("k")
    err = capsys.readouterr().err
    assert "ValueError: bad position 3" in err and "services/ros/highgui" not in err


# -- the mouse ------------------------------------------------------------------------------------


def test_mouse_events_reach_the_callback_with_their_coordinates_flags_and_param(gui: Gui) -> None:
    events: list[tuple[int, int, int, int, Any]] = []
    gui.cv2.imshow("w", np.zeros((100, 100), np.uint8))
    gui.cv2.setMouseCallback("w", lambda *args: events.append(args), "mine")
    assert gui.host.descriptions[-1].windows[0].mouse is True
    for x in range(5):  # moves in a row fold into the newest
        gui.send(window="w", kind="mouse", event=cv2.EVENT_MOUSEMOVE, x=x, y=1, flags=0)
    gui.send(window="w", kind="mouse", event=cv2.EVENT_LBUTTONDOWN, x=40, y=30, flags=cv2.EVENT_FLAG_LBUTTON | cv2.EVENT_FLAG_SHIFTKEY)
    gui.send(window="w", kind="mouse", event=cv2.EVENT_MOUSEMOVE, x=41, y=30, flags=cv2.EVENT_FLAG_LBUTTON)
    gui.send(window="w", kind="mouse", event=cv2.EVENT_MOUSEWHEEL, x=41, y=30, flags=-120 << 16)
    gui.cv2.waitKey(1)
    assert events == [
        (cv2.EVENT_MOUSEMOVE, 4, 1, 0, "mine"),
        (cv2.EVENT_LBUTTONDOWN, 40, 30, cv2.EVENT_FLAG_LBUTTON | cv2.EVENT_FLAG_SHIFTKEY, "mine"),
        (cv2.EVENT_MOUSEMOVE, 41, 30, cv2.EVENT_FLAG_LBUTTON, "mine"),
        (cv2.EVENT_MOUSEWHEEL, 41, 30, -120 << 16, "mine"),
    ]
    assert gui.cv2.getMouseWheelDelta(events[-1][3]) == -120  # the headless build lacks it; served


def test_input_for_a_window_closed_since_is_dropped_but_keys_are_kept(gui: Gui) -> None:
    events: list[tuple[Any, ...]] = []
    gui.cv2.namedWindow("w")
    gui.cv2.setMouseCallback("w", lambda *args: events.append(args))
    gui.send(window="w", kind="mouse", event=cv2.EVENT_LBUTTONDOWN, x=1, y=1, flags=1)
    gui.send(window="w", kind="key", key=ord("a"))
    gui.cv2.destroyWindow("w")
    assert gui.cv2.waitKey(1) == ord("a")
    assert events == []


@pytest.mark.parametrize(
    ("fields", "says"),
    [
        ({"window": "nope", "kind": "key", "key": 1}, r"no window 'nope' \(open: 'w'\)"),
        ({"window": "w", "kind": "key", "key": -2}, "a key code is 0 or more"),
        ({"window": "w", "kind": "mouse", "event": 12}, "EVENT_\\* codes, 0..11, not 12"),
        ({"window": "w", "kind": "trackbar", "trackbar": "x", "value": 1}, "no trackbar 'x' \\(it has: t\\)"),
        ({"window": "w", "kind": "trackbar", "trackbar": "t", "value": 11}, "goes from 0 to 10, not to 11"),
        ({"window": "w", "kind": "wave"}, "kind is one of key, mouse, trackbar, not 'wave'"),
    ],
)
def test_a_viewers_input_that_does_not_fit_is_refused_with_the_reason(gui: Gui, fields: dict[str, Any], says: str) -> None:
    gui.cv2.namedWindow("w")
    gui.cv2.createTrackbar("t", "w", 0, 10, lambda pos: None)
    answer = gui.send(**fields)
    assert answer.success is False
    assert re.search(says, answer.message), answer.message
    assert gui.cv2.waitKey(1) == -1  # nothing was queued


# -- errors ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "says"),
    [
        (lambda c: c.createTrackbar("t", "nowhere", 0, 10, print), r"createTrackbar\('t', 'nowhere', ...\): there is no window 'nowhere' \(none is open\): call cv2.namedWindow\('nowhere'\) first"),
        (lambda c: c.setMouseCallback("nowhere", print), "there is no window 'nowhere'"),
        (lambda c: c.getTrackbarPos("x", "w"), r"window 'w' has no trackbar 'x' \(it has: none\)"),
        (lambda c: c.setTrackbarPos("x", "w", 1), "has no trackbar 'x'"),
        (lambda c: c.createTrackbar("t", "w", 0, 10, None), "onChange must be a function"),
        (lambda c: c.createTrackbar("t", "w", 0, -1, print), "count is the slider's largest position, 0 or more, not -1"),
        (lambda c: c.setMouseCallback("w", 3), "onMouse must be a function"),
        (lambda c: c.waitKey(0.5), "delay must be an integer, not 0.5"),
        (lambda c: c.namedWindow(3), "winname must be a str, not int"),
        (lambda c: c.resizeWindow("w", 0, 10), "width and height must be positive"),
        (lambda c: c.resizeWindow("w", 10), "give a width and a height"),
        (lambda c: c.getWindowImageRect("nowhere"), "there is no window 'nowhere'"),
    ],
)
def test_a_wrong_call_is_a_cv2_error_that_says_what_to_do(gui: Gui, call: Callable[[HighGuiFunctions], Any], says: str) -> None:
    if "nowhere" not in says and "winname must" not in says:
        gui.cv2.namedWindow("w")
    with pytest.raises(cv2.error, match=says):
        call(gui.cv2)


def test_keyword_arguments_as_opencv_names_them(gui: Gui) -> None:
    gui.cv2.namedWindow(winname="w", flags=cv2.WINDOW_NORMAL)
    gui.cv2.imshow(winname="w", mat=np.zeros((2, 2), np.uint8))
    gui.cv2.createTrackbar(trackbarName="t", windowName="w", value=1, count=5, onChange=print)
    gui.cv2.setTrackbarPos(trackbarname="t", winname="w", pos=2)
    assert gui.cv2.getTrackbarPos(trackbarname="t", winname="w") == 2
    gui.cv2.setMouseCallback(windowName="w", onMouse=print, param=None)
    assert gui.cv2.waitKey(delay=1) == -1


# -- installing into cv2 ---------------------------------------------------------------------------


def _fake_cv2(framework: str) -> types.ModuleType:
    module = types.ModuleType("cv2")
    module.currentUIFramework = lambda: framework  # type: ignore[attr-defined]
    module.imshow = module.selectROI = module.GaussianBlur = object()  # type: ignore[attr-defined]
    return module


def test_skydeck_serves_the_windows_without_a_window_system_or_a_display(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DISPLAY", ":0")
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert serves_windows(_fake_cv2("")) is True  # headless OpenCV (the vision extra)
    assert serves_windows(_fake_cv2("GTK3")) is False  # a desktop: OpenCV's own windows
    monkeypatch.delenv("DISPLAY")
    assert serves_windows(_fake_cv2("GTK3")) is True  # no display to open them on
    monkeypatch.setenv("WAYLAND_DISPLAY", "wayland-0")
    assert serves_windows(_fake_cv2("QT5")) is False


def test_install_replaces_highgui_only_and_only_once(monkeypatch: pytest.MonkeyPatch) -> None:
    module = _fake_cv2("")
    blur = module.GaussianBlur  # type: ignore[attr-defined]
    install(module)
    served = module.imshow  # type: ignore[attr-defined]
    assert served.__self__.__class__ is HighGuiFunctions and module.GaussianBlur is blur  # type: ignore[attr-defined]
    assert not hasattr(module, "displayOverlay")  # only what the module has
    with pytest.raises(cv2.error, match="cv2.selectROI is not provided by Skydeck's dashboard windows"):
        module.selectROI("w", None)  # type: ignore[attr-defined]
    install(module)
    assert module.imshow is served  # type: ignore[attr-defined]
    desktop = _fake_cv2("GTK3")
    monkeypatch.setenv("DISPLAY", ":0")
    install(desktop)
    assert desktop.imshow is not None and not hasattr(desktop, "_skydeck_highgui")  # left alone


def test_window_names_become_ros_name_tokens() -> None:
    assert window_token("video_window", set()) == "video_window"
    assert window_token("Binary Window!", set()) == "Binary_Window_"
    assert window_token("3d view", set()) == "w_3d_view"
    assert window_token("", set()) == "w_"
    assert window_token("windows", set()) == "windows_2"  # the description's own name
    assert window_token("a b", {"a_b"}) == "a_b_2"


def _until(predicate: Callable[[], bool], timeout_s: float = 5.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError("timed out")
        time.sleep(0.005)
