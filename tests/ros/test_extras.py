"""A ROS program that imports a module of an extra that is not installed (OpenCV for cv_bridge)
is told in one line what to install; with the extra, the names are the façade and OpenCV."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

from services.ros.extras import EXTRAS, MissingExtraError

pytestmark = [pytest.mark.timeout(60), pytest.mark.usefixtures("ros_imports")]

REPO = Path(__file__).resolve().parents[2]


def test_cv_bridge_without_opencv_says_how_to_install_it(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(EXTRAS, "cv_bridge", ("an_opencv_not_installed", "OpenCV", "vision"))
    with pytest.raises(MissingExtraError) as raised:
        importlib.import_module("cv_bridge")
    assert str(raised.value) == (
        "`cv_bridge` needs OpenCV, which is in Skydeck's vision extra, not installed here: "
        "install it with `make install-vision` (or `pip install 'skydeck[vision]'`)"
    )
    assert isinstance(raised.value, ImportError)


def test_cv2_itself_without_opencv_says_the_same(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(EXTRAS, "cv2", ("an_opencv_not_installed", "OpenCV", "vision"))
    monkeypatch.delitem(sys.modules, "cv2", raising=False)
    with pytest.raises(MissingExtraError, match=r"^`cv2` needs OpenCV, which is in Skydeck's vision extra"):
        importlib.import_module("cv2")


def test_with_the_extra_cv_bridge_is_the_facade_and_cv2_is_opencv() -> None:
    pytest.importorskip("cv2", reason="the vision extra is not installed: make install-vision")
    assert importlib.import_module("cv_bridge") is importlib.import_module("services.ros.cv_bridge")
    assert importlib.import_module("cv2").__name__ == "cv2"


def test_skydeck_run_prints_the_line_alone(tmp_path: Path) -> None:
    path = tmp_path / "node.py"
    path.write_text(
        "import services.ros.extras as extras\n"
        "extras.EXTRAS['cv_bridge'] = ('an_opencv_not_installed', 'OpenCV', 'vision')\n"
        "from cv_bridge import CvBridge\n"
    )
    result = subprocess.run(
        [sys.executable, "-m", "services.cli", "run", str(path)], cwd=REPO, capture_output=True, text=True, timeout=60
    )
    assert result.returncode == 1 and "Traceback" not in result.stderr
    assert result.stderr.startswith("skydeck: error: `cv_bridge` needs OpenCV") and result.stderr.count("\n") == 1
