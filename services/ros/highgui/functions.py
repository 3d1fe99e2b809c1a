"""OpenCV's HighGUI functions as a program calls them (``cv2.imshow(winname, mat)``...), served
by :class:`~services.ros.highgui.windows.HighGui`: the names, parameter names (for keywords) and
return values of OpenCV's Python bindings, every argument checked with a message that says what
was wrong.

Where OpenCV is vague and Skydeck is not: a trackbar or mouse callback set on a window that is
not open, and a trackbar that does not exist, are errors (OpenCV's backends differ: some do
nothing, some return -1), since either is a typo that would otherwise fail silently.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import Any

import cv2

from services.ros.highgui.display import displayable
from services.ros.highgui.errors import HighGuiError
from services.ros.highgui.windows import HighGui

__all__ = ["NOT_PROVIDED", "SERVED", "HighGuiFunctions"]

# The cv2 functions Skydeck serves (each a method below, of the same name).
SERVED = (
    "namedWindow",
    "imshow",
    "waitKey",
    "waitKeyEx",
    "pollKey",
    "createTrackbar",
    "getTrackbarPos",
    "setTrackbarPos",
    "setTrackbarMin",
    "setTrackbarMax",
    "setMouseCallback",
    "getMouseWheelDelta",
    "destroyWindow",
    "destroyAllWindows",
    "moveWindow",
    "resizeWindow",
    "setWindowTitle",
    "getWindowProperty",
    "setWindowProperty",
    "getWindowImageRect",
    "startWindowThread",
)
# HighGUI functions the dashboard's windows do not have: one clear line instead of OpenCV's
# "rebuild the library with GTK+" (the headless build's answer).
NOT_PROVIDED = (
    "selectROI",
    "selectROIs",
    "displayOverlay",
    "displayStatusBar",
    "addText",
    "createButton",
    "fontQt",
    "loadWindowParameters",
    "saveWindowParameters",
    "setOpenGlContext",
    "setOpenGlDrawCallback",
    "updateWindow",
    "imshow_opengl",
)


def _name(value: Any, what: str, doing: str) -> str:
    if not isinstance(value, str):
        raise HighGuiError(f"{doing}: {what} must be a str, not {type(value).__name__}")
    return value


def _int(value: Any, what: str, doing: str) -> int:
    try:
        return operator.index(value)
    except TypeError:
        raise HighGuiError(f"{doing}: {what} must be an integer, not {value!r}") from None


def _callable(value: Any, what: str, doing: str) -> Callable[..., Any]:
    if not callable(value):
        raise HighGuiError(f"{doing}: {what} must be a function, not {value!r}")
    return value  # type: ignore[no-any-return]


def not_provided(name: str) -> Callable[..., Any]:
    """A stand-in for a HighGUI function the dashboard's windows do not have."""

    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise HighGuiError(
            f"cv2.{name} is not provided by Skydeck's dashboard windows (yet): "
            "what they provide is in docs/ros.md (OpenCV windows)"
        )

    refuse.__name__ = refuse.__qualname__ = name
    return refuse


class HighGuiFunctions:
    """The served functions, bound to one :class:`HighGui` (the process's windows)."""

    def __init__(self, gui: HighGui) -> None:
        self.gui = gui

    # -- windows and images -------------------------------------------------------------------

    def namedWindow(self, winname: str, flags: int = cv2.WINDOW_AUTOSIZE) -> None:
        """Open a window (a panel in the dashboard's Windows tab)."""
        doing = "cv2.namedWindow"
        self.gui.window(_name(winname, "winname", doing), _int(flags, "flags", doing))

    def imshow(self, winname: str, mat: Any) -> None:
        """Show ``mat`` in the window (opened if need be); it reaches the dashboard at the next waitKey."""
        name = _name(winname, "winname", "cv2.imshow")
        self.gui.show(name, displayable(name, mat))

    def destroyWindow(self, winname: str) -> None:
        """Close a window (nothing happens if it is not open, as in OpenCV)."""
        self.gui.destroy(_name(winname, "winname", "cv2.destroyWindow"))

    def destroyAllWindows(self) -> None:
        """Close every window."""
        self.gui.destroy_all()

    def moveWindow(self, winname: str, x: int, y: int) -> None:
        """Accepted; the dashboard lays its panels out itself."""
        doing = f"cv2.moveWindow({winname!r}, ...)"
        _int(x, "x", doing)
        _int(y, "y", doing)
        self.gui.existing(_name(winname, "winname", doing), doing)

    def resizeWindow(self, winname: str, width: Any, height: int | None = None) -> None:
        """The size the window's image is shown at (``resizeWindow(name, w, h)`` or ``(name, (w, h))``)."""
        doing = f"cv2.resizeWindow({winname!r}, ...)"
        if height is None:
            try:
                width, height = width
            except (TypeError, ValueError):
                raise HighGuiError(f"{doing}: give a width and a height, or a (width, height) pair") from None
        size = (_int(width, "width", doing), _int(height, "height", doing))
        if min(size) <= 0:
            raise HighGuiError(f"{doing}: width and height must be positive, not {size}")
        self.gui.change(_name(winname, "winname", doing), doing, display_size=size)

    def setWindowTitle(self, winname: str, title: str) -> None:
        """The title the dashboard shows above the window."""
        doing = f"cv2.setWindowTitle({winname!r}, ...)"
        self.gui.change(_name(winname, "winname", doing), doing, title=_name(title, "title", doing))

    def getWindowProperty(self, winname: str, prop_id: int) -> float:
        """``WND_PROP_VISIBLE``: 1.0 while the window is open, else 0.0; ``WND_PROP_AUTOSIZE``:
        from the window's flags; the others as a window that is not full screen, not on top and
        without OpenGL says them; -1.0 for a window that is not open."""
        doing = "cv2.getWindowProperty"
        name, prop = _name(winname, "winname", doing), _int(prop_id, "prop_id", doing)
        is_open = name in self.gui.names()
        if prop == cv2.WND_PROP_VISIBLE:
            return 1.0 if is_open else 0.0
        if not is_open:
            return -1.0
        if prop == cv2.WND_PROP_AUTOSIZE:
            return float(self.gui.existing(name, doing).flags & cv2.WINDOW_AUTOSIZE)
        if prop in (cv2.WND_PROP_OPENGL, cv2.WND_PROP_VSYNC):
            return -1.0
        return 0.0

    def setWindowProperty(self, winname: str, prop_id: int, prop_value: float) -> None:
        """Accepted for an open window; the dashboard lays its panels out itself."""
        doing = f"cv2.setWindowProperty({winname!r}, ...)"
        _int(prop_id, "prop_id", doing)
        self.gui.existing(_name(winname, "winname", doing), doing)

    def getWindowImageRect(self, winname: str) -> tuple[int, int, int, int]:
        """(0, 0, width, height) of the window's image as shown."""
        doing = "cv2.getWindowImageRect"
        window = self.gui.existing(_name(winname, "winname", doing), doing)
        width, height = window.display_size
        if not width and window.image is not None:
            height, width = window.image.shape[:2]
        return (0, 0, width, height)

    def startWindowThread(self) -> int:
        """Nothing to start: the dashboard's windows need no thread of their own."""
        return 0

    # -- keys: the event loop -----------------------------------------------------------------

    def waitKey(self, delay: int = 0) -> int:
        """Wait ``delay`` ms (0: for ever) for a key typed in a window; its code's low byte, or -1.
        Images go out and trackbar and mouse callbacks run during the wait, in this thread."""
        code = self.gui.wait_key(self._timeout(delay, "cv2.waitKey"))
        return code if code == -1 else code & 0xFF

    def waitKeyEx(self, delay: int = 0) -> int:
        """As waitKey, with the whole key code (arrows: 65361..65364)."""
        return self.gui.wait_key(self._timeout(delay, "cv2.waitKeyEx"))

    def pollKey(self) -> int:
        """As waitKeyEx, without waiting."""
        return self.gui.wait_key(0.0)

    @staticmethod
    def _timeout(delay: Any, doing: str) -> float | None:
        milliseconds = _int(delay, "delay", doing)
        return None if milliseconds <= 0 else milliseconds / 1000.0

    # -- trackbars and the mouse --------------------------------------------------------------

    def createTrackbar(self, trackbarName: str, windowName: str, value: int, count: int, onChange: Callable[[int], Any]) -> None:
        """A slider under the window, 0..count at value; ``onChange(pos)`` runs when it moves."""
        doing = f"cv2.createTrackbar({trackbarName!r}, {windowName!r}, ...)"
        name = _name(trackbarName, "trackbarName", doing)
        window = _name(windowName, "windowName", doing)
        value, count = _int(value, "value", doing), _int(count, "count", doing)
        if count < 0:
            raise HighGuiError(f"{doing}: count is the slider's largest position, 0 or more, not {count}")
        self.gui.create_trackbar(name, window, value, count, _callable(onChange, "onChange", doing))

    def getTrackbarPos(self, trackbarname: str, winname: str) -> int:
        """The slider's position."""
        doing = f"cv2.getTrackbarPos({trackbarname!r}, {winname!r})"
        name, window = _name(trackbarname, "trackbarname", doing), _name(winname, "winname", doing)
        return self.gui.trackbar(name, window, doing).value

    def setTrackbarPos(self, trackbarname: str, winname: str, pos: int) -> None:
        """Move the slider (within its range); its ``onChange`` runs here if it moved."""
        doing = f"cv2.setTrackbarPos({trackbarname!r}, {winname!r}, ...)"
        name, window = _name(trackbarname, "trackbarname", doing), _name(winname, "winname", doing)
        self.gui.move_trackbar(name, window, _int(pos, "pos", doing), doing)

    def setTrackbarMin(self, trackbarname: str, winname: str, minval: int) -> None:
        """The slider's smallest position."""
        doing = f"cv2.setTrackbarMin({trackbarname!r}, {winname!r}, ...)"
        name, window = _name(trackbarname, "trackbarname", doing), _name(winname, "winname", doing)
        self.gui.set_trackbar_range(name, window, doing, minimum=_int(minval, "minval", doing))

    def setTrackbarMax(self, trackbarname: str, winname: str, maxval: int) -> None:
        """The slider's largest position."""
        doing = f"cv2.setTrackbarMax({trackbarname!r}, {winname!r}, ...)"
        name, window = _name(trackbarname, "trackbarname", doing), _name(winname, "winname", doing)
        self.gui.set_trackbar_range(name, window, doing, maximum=_int(maxval, "maxval", doing))

    def setMouseCallback(self, windowName: str, onMouse: Callable[..., Any], param: Any = None) -> None:
        """``onMouse(event, x, y, flags, param)`` for mouse events over the window's image, in image pixels."""
        doing = f"cv2.setMouseCallback({windowName!r}, ...)"
        name = _name(windowName, "windowName", doing)
        self.gui.change(name, doing, on_mouse=_callable(onMouse, "onMouse", doing), mouse_param=param)

    def getMouseWheelDelta(self, flags: int) -> int:
        """The wheel's turn in a MOUSEWHEEL/MOUSEHWHEEL event's flags (120 a notch; positive: away, or right)."""
        return _int(flags, "flags", "cv2.getMouseWheelDelta") >> 16
