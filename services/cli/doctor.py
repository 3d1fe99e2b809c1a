"""``skydeck doctor`` (roswtf / ros2 doctor): checks the set-up and says what to do for each problem.

Each check prints one line, ``[ok]``, ``[warn]`` or ``[FAIL]``, and for a problem the fix after
``->``. The exit status is 1 if any check failed, so scripts and CI can use it.
"""

from __future__ import annotations

import argparse
import email.utils
import importlib.util
import shutil
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

from services.cli.core_client import core_url, get
from services.runtime.http_client import HttpError

__all__ = ["add_parser"]

_REPO = Path(__file__).resolve().parents[2]
_DEFAULT_PORTS = {8000: "core", 8001: "sim", 8002: "perception", 8003: "control", 8004: "ai", 9090: "rosbridge", 8765: "Foxglove"}
_CHROMIUM = Path("/usr/bin/chromium")
_MAX_SKEW_S = 2.0
_NEEDED_PYTHON = (3, 11)  # a tuple here, not in the test: an older Python must be told, not fail to parse


@dataclass(frozen=True)
class Check:
    """One finding: ``status`` is ok, warn or FAIL; ``fix`` says what to do about a problem."""

    status: str
    what: str
    fix: str = ""

    def line(self) -> str:
        return f"[{self.status}] {self.what}" + (f" -> {self.fix}" if self.fix else "")


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser("doctor", help="check Python, the venv, the core, clocks, ports and test browser; say what to fix")
    p.set_defaults(func=_doctor)


def _doctor(args: argparse.Namespace) -> int:
    checks: list[Callable[[], list[Check]]] = [_python, _venv, _packages, _core_and_clock, _ports, _browser]
    failed = 0
    for check in checks:
        for finding in check():
            print(finding.line(), flush=True)
            failed += finding.status == "FAIL"
    print(f"{failed} problem(s) to fix" if failed else "all checks passed")
    return 1 if failed else 0


def _python() -> list[Check]:
    found = ".".join(str(part) for part in sys.version_info[:3])
    if sys.version_info[:2] >= _NEEDED_PYTHON:
        return [Check("ok", f"Python {found}")]
    return [Check("FAIL", f"Python {found}: Skydeck needs 3.11 or newer", "install Python 3.11 and run `make install`")]


def _venv() -> list[Check]:
    in_venv = sys.prefix != sys.base_prefix
    where = Check("ok", f"virtual environment {sys.prefix}") if in_venv else Check(
        "warn", f"not in a virtual environment ({sys.prefix})", "run `make install`, then use .venv/bin/skydeck"
    )
    try:
        installed = Check("ok", f"skydeck {version('skydeck')} installed")
    except PackageNotFoundError:
        installed = Check("FAIL", "skydeck is not installed in this Python", "run `make install` in the repository")
    return [where, installed]


def _packages() -> list[Check]:
    """Every pin of the runtime lock (when run from the repository) installed at that version."""
    lock = _REPO / "requirements-runtime.lock"
    if not lock.is_file():
        return []
    wrong: list[str] = []
    for line in lock.read_text().splitlines():
        if "==" not in line or line.startswith((" ", "#")):
            continue
        name, pinned = line.split("==", 1)
        pinned = pinned.split()[0].rstrip("\\").strip()
        try:
            have = version(name.strip())
        except PackageNotFoundError:
            wrong.append(f"{name} missing")
            continue
        if have != pinned:
            wrong.append(f"{name} {have} (lock: {pinned})")
    if wrong:
        shown = ", ".join(wrong[:4]) + (f" and {len(wrong) - 4} more" if len(wrong) > 4 else "")
        return [Check("FAIL", f"packages differ from requirements-runtime.lock: {shown}", "run `make install`")]
    return [Check("ok", "packages match requirements-runtime.lock")]


def _core_and_clock() -> list[Check]:
    url = core_url()
    try:
        reply = get(url + "/health", timeout_s=3.0)
    except HttpError as error:
        return [
            Check(
                "FAIL",
                f"core at {url} not reachable ({error})",
                "start it with `skydeck core` or `make up`, or set SKYDECK_CORE_URL to where it runs",
            )
        ]
    if reply.status != 200:
        return [Check("FAIL", f"core at {url} answered {reply.status} to /health", "is another server on that port?")]
    nodes = reply.json().get("nodes", "?") if reply.headers.get("content-type", "").startswith("application/json") else "?"
    found = [Check("ok", f"core at {url} answers ({nodes} node(s) registered)")]
    served = reply.headers.get("date")
    if served:
        skew = abs(email.utils.parsedate_to_datetime(served).timestamp() - time.time())
        if skew > _MAX_SKEW_S:
            found.append(
                Check("warn", f"clock skew with the core: {skew:.1f} s", "sync both machines' clocks (NTP): stamps and delays compare them")
            )
        else:
            found.append(Check("ok", f"clock skew with the core under {_MAX_SKEW_S:g} s"))
    return found


def _ports() -> list[Check]:
    from services.runtime.ports import port_is_free

    taken = [f"{port} ({role})" for port, role in _DEFAULT_PORTS.items() if not port_is_free(port)]
    if not taken:
        return [Check("ok", "default ports free: " + ", ".join(str(port) for port in _DEFAULT_PORTS))]
    return [
        Check(
            "warn",
            f"ports in use: {', '.join(taken)}",
            "fine if Skydeck is running there; otherwise stop what holds them or use `skydeck launch --base-port N`",
        )
    ]


def _browser() -> list[Check]:
    found: list[Check] = []
    chromium = _CHROMIUM if _CHROMIUM.exists() else (Path(p) if (p := shutil.which("chromium")) else None)
    if chromium is None:
        found.append(Check("FAIL", "no Chromium for the browser tests", "apt-get install chromium (Debian's; `make test` does it as root)"))
    else:
        found.append(Check("ok", f"Chromium at {chromium}"))
    if importlib.util.find_spec("playwright") is None:
        found.append(Check("FAIL", "Playwright is not installed", "run `make install` (it is in requirements.lock)"))
    else:
        found.append(Check("ok", "Playwright installed"))
    swagger = _REPO / "web_ui" / "vendor" / "node_modules" / "swagger-ui-dist"
    if (_REPO / "web_ui").is_dir() and not swagger.is_dir():
        found.append(Check("warn", "Swagger UI missing: /docs has no page", "run `make install` (npm ci in web_ui/vendor)"))
    return found
