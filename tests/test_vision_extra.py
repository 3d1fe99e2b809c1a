"""The vision extra (cv_bridge's OpenCV) installs apart from the default, pinned with hashes:
requirements-vision.lock is pyproject.toml's `vision` extra pinned to requirements.lock, and
`make test` installs it."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from tests.test_containers import _pins

pytestmark = pytest.mark.timeout(30)

ROOT = Path(__file__).resolve().parents[1]
REGENERATE_VISION_LOCK = (
    ".venv/bin/uv pip compile pyproject.toml --extra vision -c requirements.lock"
    " --python-version 3.11 --generate-hashes -o requirements-vision.lock"
)


def test_the_vision_lock_pins_opencv_and_agrees_with_the_lock() -> None:
    vision = _pins(ROOT / "requirements-vision.lock")
    full = _pins(ROOT / "requirements.lock")
    version, hashes = vision["opencv-python-headless"]
    assert version.startswith("4.") and hashes, "OpenCV 4, hash-pinned"
    for name, pin in vision.items():
        if name != "opencv-python-headless":
            assert pin == full.get(name), f"{name}: requirements-vision.lock differs from requirements.lock; regenerate: {REGENERATE_VISION_LOCK}"
    extra = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]["vision"]
    assert [re.match(r"[A-Za-z0-9._-]+", r).group(0) for r in extra] == ["opencv-python-headless"]  # type: ignore[union-attr]
    assert "opencv" not in (ROOT / "requirements.lock").read_text()  # the default install stays light


def test_make_test_installs_the_extra_with_hashes() -> None:
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^test: .*\binstall-vision\b", makefile, re.M)
    assert "--require-hashes --no-deps -r requirements-vision.lock" in makefile
