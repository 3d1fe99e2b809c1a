"""What a page read, by name, and the topics the core lists with no type (what a subscription
to a name nobody publishes would leave: `skydeck topic list -t` showing `name []`)."""

from __future__ import annotations

import os
import subprocess
import sys
from urllib.parse import unquote, urlsplit

import httpx

from tests.web_ui.system import REPO


def world_topics(core_url: str, world: str) -> set[str]:
    """The absolute names of ``world``'s topics, from its description (GET /api/config)."""
    topics = httpx.get(core_url + "/api/config", timeout=5).json()["worlds"][world]["topics"]
    return {name for name in topics.values() if name.startswith("/")}


def read_topics(urls: list[str], core_url: str) -> set[str]:
    """The topics a page opened a socket on (its ws:// URLs to the core)."""
    core = urlsplit(core_url).netloc
    return {unquote(urlsplit(u).path) for u in urls if u.startswith("ws://") and urlsplit(u).netloc == core}


def untyped_topics(core_url: str) -> list[str]:
    """`skydeck topic list -t`'s lines for topics without a type."""
    listed = subprocess.run(
        [sys.executable, "-m", "services.cli", "topic", "list", "-t"],
        cwd=REPO, env={**os.environ, "SKYDECK_CORE_URL": core_url}, capture_output=True, text=True, timeout=30, check=True,
    )  # fmt: skip
    lines = listed.stdout.strip().splitlines()
    assert lines, "topic list printed nothing"
    return [line for line in lines if line.rstrip().endswith("[]")]
