"""The process's OpenCV windows and what viewers did in them, kept as HighGUI keeps them.

HighGUI's model, which programs rely on: ``imshow`` only stores the image; the window system
runs inside ``waitKey``, which is where images reach the screen and where keys, mouse events and
trackbar moves are handled, so trackbar and mouse callbacks run in the thread that calls
``waitKey`` (or ``setTrackbarPos``), never behind the program's back. Here the screen is the
dashboard: during ``waitKey`` a window's newest image goes out as a JPEG, at most ``max_rate_hz``
times a second and only while someone watches it, encoded once whoever watches; a viewer's
input arrives on the bridge's loop (:meth:`HighGui.take_input`) and waits here for the program's
next ``waitKey``. ``waitKey(ms)`` waits ``ms`` milliseconds when no key comes, so a loop paced by
it runs as fast as it would on a desktop.

How the windows reach the dashboard (topics, a service, which node) is the :class:`Host`'s
business (:mod:`services.ros.highgui.host`); nothing here knows about nodes or sockets.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from services.ros.highgui.display import encode_jpeg
from services.ros.highgui.errors import HighGuiError
from services.ros.tracebacks import user_traceback
from shared_models.skydeck_opencv import Trackbar as TrackbarMessage
from shared_models.skydeck_opencv import Window as WindowMessage
from shared_models.skydeck_opencv import WindowInputRequest, WindowInputResponse, Windows

__all__ = ["MAX_RATE_HZ", "Host", "HighGui", "InputHandler", "Trackbar", "Window"]

MAX_RATE_HZ = 15.0  # images a second per window at most, whatever the program shows
MAX_INPUTS = 256  # inputs waiting for waitKey; the oldest go first (a program that never asks)
LAST_MOUSE_EVENT = 11  # cv2.EVENT_MOUSEHWHEEL: MOUSEMOVE (0) ... MOUSEHWHEEL (11)
_MOUSEMOVE = 0
_IDLE_WAIT_S = 0.1  # the longest single wait: Ctrl-C and new images are seen this soon

InputHandler = Callable[[WindowInputRequest], WindowInputResponse]


class Host(Protocol):
    """Where the windows are shown (the dashboard, through a node's topics and service)."""

    def add_window(self, name: str) -> str:
        """Make room for window ``name``; the topic its images go out on."""

    def watched(self, topic: str) -> bool:
        """Whether anyone reads ``topic`` now."""

    def publish_image(self, topic: str, jpeg: bytes) -> None:
        """Send one image (never blocks)."""

    def publish_windows(self, windows: Windows) -> None:
        """Say which windows there are (never blocks)."""


@dataclass
class Trackbar:
    """A trackbar: its position within [minimum, maximum] and the program's ``onChange``."""

    name: str
    value: int
    minimum: int
    maximum: int
    on_change: Callable[[int], Any]


@dataclass
class Window:
    """A window: its newest image (shown as it was at ``imshow``), trackbars, mouse callback."""

    name: str
    topic: str
    flags: int
    title: str
    image: np.ndarray | None = None
    dirty: bool = False  # an image not sent yet
    next_send_at: float = -math.inf  # the rate limit, and how often an unwatched window is asked
    display_size: tuple[int, int] = (0, 0)
    trackbars: dict[str, Trackbar] = field(default_factory=dict)
    on_mouse: Callable[..., Any] | None = None
    mouse_param: Any = None


class HighGui:
    """Every window of this process (see the module docstring); safe from any thread.

    ``connect(take_input)`` makes the :class:`Host` when the first window opens.
    """

    def __init__(
        self,
        connect: Callable[[InputHandler], Host],
        *,
        max_rate_hz: float = MAX_RATE_HZ,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._connect = connect
        self._host: Host | None = None
        self._connecting = threading.Lock()
        self._period_s = 1.0 / max_rate_hz
        self._clock = clock
        self._state = threading.Condition(threading.RLock())  # windows and inputs
        self._windows: dict[str, Window] = {}
        self._inputs: deque[WindowInputRequest] = deque(maxlen=MAX_INPUTS)

    # -- windows ------------------------------------------------------------------------------

    def window(self, name: str, flags: int) -> Window:
        """Window ``name``, opened with ``flags`` if it is not open yet."""
        with self._state:
            window = self._windows.get(name)
        if window is not None:
            return window
        topic = self._ensure_host().add_window(name)  # may wait for the loop: outside the lock
        with self._state:
            window = self._windows.get(name)
            if window is None:
                window = self._windows[name] = Window(name, topic, flags, name)
                self._describe()
            return window

    def existing(self, name: str, doing: str) -> Window:
        """Window ``name``, or an error for ``doing`` that names the open windows."""
        with self._state:
            window = self._windows.get(name)
            if window is None:
                raise HighGuiError(f"{doing}: there is no window {name!r} ({self._open_windows()}): call cv2.namedWindow({name!r}) first")
            return window

    def _open_windows(self) -> str:
        return "open: " + ", ".join(repr(n) for n in self._windows) if self._windows else "none is open"

    def names(self) -> list[str]:
        with self._state:
            return list(self._windows)

    def show(self, name: str, image: np.ndarray) -> None:
        """``imshow``: keep ``image`` (already a copy) as the window's newest."""
        window = self.window(name, _AUTOSIZE)
        with self._state:
            resized = window.image is None or window.image.shape[:2] != image.shape[:2]
            window.image = image
            window.dirty = True
            if resized:
                self._describe()

    def destroy(self, name: str) -> None:
        with self._state:
            if self._windows.pop(name, None) is not None:
                self._describe()

    def destroy_all(self) -> None:
        with self._state:
            if self._windows:
                self._windows.clear()
                self._describe()

    def change(self, name: str, doing: str, **changes: Any) -> None:
        """Set ``changes`` (``title``, ``display_size``, ``on_mouse``...) on an open window."""
        with self._state:
            window = self.existing(name, doing)
            for attribute, value in changes.items():
                setattr(window, attribute, value)
            self._describe()

    # -- trackbars ----------------------------------------------------------------------------

    def create_trackbar(self, name: str, window_name: str, value: int, count: int, on_change: Callable[[int], Any]) -> None:
        """A trackbar over [0, count] at ``value`` (clamped); a second one of the same name
        replaces the first, as in OpenCV. ``on_change`` is not called now (OpenCV does not)."""
        with self._state:
            window = self.existing(window_name, f"cv2.createTrackbar({name!r}, {window_name!r}, ...)")
            window.trackbars[name] = Trackbar(name, min(max(value, 0), count), 0, count, on_change)
            self._describe()

    def trackbar(self, name: str, window_name: str, doing: str) -> Trackbar:
        with self._state:
            window = self.existing(window_name, doing)
            trackbar = window.trackbars.get(name)
            if trackbar is None:
                names = ", ".join(repr(n) for n in window.trackbars) or "none"
                raise HighGuiError(f"{doing}: window {window_name!r} has no trackbar {name!r} (it has: {names})")
            return trackbar

    def move_trackbar(self, name: str, window_name: str, value: int, doing: str) -> None:
        """``setTrackbarPos``: move it (clamped) and, if it moved, call its ``onChange`` here."""
        self._move(self.trackbar(name, window_name, doing), value)

    def set_trackbar_range(self, name: str, window_name: str, doing: str, *, minimum: int | None = None, maximum: int | None = None) -> None:
        """``setTrackbarMin``/``Max``; the position is clamped into the new range (no callback)."""
        with self._state:
            trackbar = self.trackbar(name, window_name, doing)
            trackbar.minimum = trackbar.minimum if minimum is None else minimum
            trackbar.maximum = trackbar.maximum if maximum is None else maximum
            trackbar.maximum = max(trackbar.maximum, trackbar.minimum)
            trackbar.value = min(max(trackbar.value, trackbar.minimum), trackbar.maximum)
            self._describe()

    def _move(self, trackbar: Trackbar, value: int) -> None:
        with self._state:
            value = min(max(value, trackbar.minimum), trackbar.maximum)
            if value == trackbar.value:
                return
            trackbar.value = value
            self._describe()
        _run_callback(trackbar.on_change, value)

    # -- the event loop: waitKey --------------------------------------------------------------

    def wait_key(self, timeout_s: float | None) -> int:
        """Show what is due, handle what viewers did (callbacks run here) and return the first
        key's code, or -1 once ``timeout_s`` has passed without one (None: wait for a key)."""
        deadline = None if timeout_s is None else self._clock() + timeout_s
        while True:
            self._send_images()
            while (request := self._next_input()) is not None:
                key = self._handle(request)
                if key is not None:
                    return key
            with self._state:
                if self._inputs:
                    continue
                now = self._clock()
                if deadline is not None and now >= deadline:
                    return -1
                wait_s = _IDLE_WAIT_S if deadline is None else min(_IDLE_WAIT_S, deadline - now)
                due = [w.next_send_at - now for w in self._windows.values() if w.dirty]
                if due:
                    wait_s = min(wait_s, max(min(due), 0.001))
                self._state.wait(wait_s)

    def _send_images(self) -> None:
        host = self._host
        if host is None:
            return
        now = self._clock()
        with self._state:
            due = [w for w in self._windows.values() if w.dirty and now >= w.next_send_at]
        for window in due:
            watched = host.watched(window.topic)
            with self._state:
                window.next_send_at = now + self._period_s
                image = window.image
                if not watched or image is None:
                    continue
                window.dirty = False
            host.publish_image(window.topic, encode_jpeg(image))  # OpenCV lets go of the GIL

    def _next_input(self) -> WindowInputRequest | None:
        with self._state:
            return self._inputs.popleft() if self._inputs else None

    def _handle(self, request: WindowInputRequest) -> int | None:
        """Act on one input; a key's code, or None."""
        if request.kind == WindowInputRequest.KEY:
            return request.key
        with self._state:
            window = self._windows.get(request.window)  # gone since: its input goes with it
            if window is None:
                return None
            trackbar = window.trackbars.get(request.trackbar)
            on_mouse, param = window.on_mouse, window.mouse_param
        if request.kind == WindowInputRequest.TRACKBAR and trackbar is not None:
            self._move(trackbar, request.value)
        elif request.kind == WindowInputRequest.MOUSE and on_mouse is not None:
            _run_callback(on_mouse, request.event, request.x, request.y, request.flags, param)
        return None

    # -- the viewers' side (the bridge's loop) ------------------------------------------------

    def take_input(self, request: WindowInputRequest) -> WindowInputResponse:
        """A viewer's key, mouse event or trackbar move: checked, then kept for ``waitKey``.
        Mouse moves in a row are folded into the newest, as a window system does."""
        with self._state:
            refusal = self._refusal(request)
            if refusal:
                return WindowInputResponse(success=False, message=refusal)
            last = self._inputs[-1] if self._inputs else None
            if _is_move(request) and last is not None and _is_move(last) and last.window == request.window:
                self._inputs[-1] = request
            else:
                self._inputs.append(request)
            self._state.notify_all()
        return WindowInputResponse(success=True, message="taken: the program sees it at its next cv2.waitKey")

    def _refusal(self, request: WindowInputRequest) -> str:
        window = self._windows.get(request.window)
        if window is None:
            return f"no window {request.window!r} ({self._open_windows()})"
        if request.kind == WindowInputRequest.KEY:
            return "" if request.key >= 0 else f"a key code is 0 or more, not {request.key}"
        if request.kind == WindowInputRequest.MOUSE:
            if 0 <= request.event <= LAST_MOUSE_EVENT:
                return ""
            return f"a mouse event is one of OpenCV's EVENT_* codes, 0..{LAST_MOUSE_EVENT}, not {request.event}"
        if request.kind == WindowInputRequest.TRACKBAR:
            trackbar = window.trackbars.get(request.trackbar)
            if trackbar is None:
                return f"window {request.window!r} has no trackbar {request.trackbar!r} (it has: {', '.join(window.trackbars) or 'none'})"
            if not trackbar.minimum <= request.value <= trackbar.maximum:
                return f"trackbar {request.trackbar!r} goes from {trackbar.minimum} to {trackbar.maximum}, not to {request.value}"
            return ""
        kinds = (WindowInputRequest.KEY, WindowInputRequest.MOUSE, WindowInputRequest.TRACKBAR)
        return f"kind is one of {', '.join(kinds)}, not {request.kind!r}"

    # -- the edge -----------------------------------------------------------------------------

    def _ensure_host(self) -> Host:
        host = self._host
        if host is None:
            with self._connecting:
                if self._host is None:
                    self._host = self._connect(self.take_input)
                host = self._host
        return host

    def _describe(self) -> None:
        """Say which windows there are; under the lock, so descriptions go out in order."""
        if self._host is None:
            return
        self._host.publish_windows(Windows(windows=[_message(w) for w in self._windows.values()]))


_AUTOSIZE = 1  # cv2.WINDOW_AUTOSIZE: imshow opens a window as namedWindow's default does


def _message(window: Window) -> WindowMessage:
    height, width = window.image.shape[:2] if window.image is not None else (0, 0)
    return WindowMessage(
        name=window.name,
        title=window.title,
        topic=window.topic,
        width=width,
        height=height,
        display_width=window.display_size[0],
        display_height=window.display_size[1],
        mouse=window.on_mouse is not None,
        trackbars=[
            TrackbarMessage(name=t.name, value=t.value, minimum=t.minimum, maximum=t.maximum)
            for t in window.trackbars.values()
        ],
    )


def _is_move(request: WindowInputRequest) -> bool:
    return request.kind == WindowInputRequest.MOUSE and request.event == _MOUSEMOVE


def _run_callback(callback: Callable[..., Any], *args: Any) -> None:
    """Call the program's callback; its exception is printed (its own traceback) and the window
    goes on, as OpenCV's Python bindings do."""
    try:
        callback(*args)
    except Exception as error:
        print(user_traceback(error), file=sys.stderr)
