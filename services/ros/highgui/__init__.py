"""OpenCV's windows in the dashboard: HighGUI served by Skydeck for programs ``skydeck run`` starts.

A course's vision node opens windows (``cv2.namedWindow``, ``imshow``, trackbars to tune its
thresholds, a mouse callback to pick a colour, ``waitKey`` to pace its loop). Where OpenCV has no
window system (the headless build of Skydeck's vision extra) or the machine no display, those
calls are served here instead, and each window is a live panel in the dashboard's Windows tab:

    cv2.imshow("video_window", frame)      ->  /NODE/opencv/video_window (CompressedImage, JPEG)
    cv2.createTrackbar("hue", "mask", ...)  ->  a slider under the panel; onChange runs in waitKey
    cv2.setMouseCallback("video_window", f) ->  clicks in the panel, in image pixels
    cv2.waitKey(5)                          ->  a key typed in the panel, or -1 after 5 ms

An adapter at the edge, as the protocols are: the rest of ``cv2`` is the real OpenCV, and only
its HighGUI functions, in the ``cv2`` module the program imports, are replaced
(:func:`install`, called by the import finder when ``cv2`` is first imported). The windows'
state and ``waitKey``'s event loop are :mod:`~services.ros.highgui.windows`; the topics and the
input service on the program's node are :mod:`~services.ros.highgui.host`.
"""

from __future__ import annotations

from types import ModuleType

from services.ros.highgui.display import serves_windows
from services.ros.highgui.errors import HighGuiError
from services.ros.highgui.functions import NOT_PROVIDED, SERVED, HighGuiFunctions, not_provided
from services.ros.highgui.host import connect
from services.ros.highgui.windows import HighGui

__all__ = ["HighGuiError", "install", "serves_windows"]

_INSTALLED = "_skydeck_highgui"


def install(cv2_module: ModuleType) -> None:
    """Serve ``cv2_module``'s HighGUI functions here, if this process needs it (idempotent)."""
    if getattr(cv2_module, _INSTALLED, None) is not None or not serves_windows(cv2_module):
        return
    functions = HighGuiFunctions(HighGui(connect))
    for name in SERVED:
        setattr(cv2_module, name, getattr(functions, name))
    for name in NOT_PROVIDED:
        if hasattr(cv2_module, name):
            setattr(cv2_module, name, not_provided(name))
    setattr(cv2_module, _INSTALLED, functions)
