"""The seeds' own ROS 2 code blocks are in the corpus verbatim (nothing reformatted them)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.ros.conftest import CORPUS

SEED = Path("/work/shared/seeds/001_e6c1d12a3b8a3e88.txt")


@pytest.mark.skipif(not SEED.is_file(), reason="the seed is not on this machine")
@pytest.mark.parametrize("name", ["send_message_skeleton.py", "receive_message_skeleton.py", "hello.py"])
def test_seed_block_is_verbatim(name: str) -> None:
    assert (CORPUS / "ros2" / name).read_text().rstrip("\n") in SEED.read_text()
