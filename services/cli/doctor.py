"""``skydeck doctor`` (roswtf / ros2 doctor): checks the set-up and says what to do for each problem.

Each check prints one line, ``[ok]``, ``[warn]`` or ``[FAIL]``, and for a problem the fix after
``->``. Two groups: what running Skydeck needs (Python, the install, the core at
``SKYDECK_CORE_URL``, clocks, ports), then what only the test suite needs (Chromium and
Playwright, docker-compose, Node for the protocol clients), whose absence is a warning. A port
held by the Skydeck the doctor found (its core, its endpoints, its nodes) is as it should be.
The exit status is 1 only if a check of the first group failed, so scripts and CI can use it:
0 means the system can run.
"""

from __future__ import annotations

import argparse
import email.utils
import importlib.util
import shutil
import sys
import time
import urllib.parse
from collections.abc import Callable
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

from services.cli.core_client import core_url, get
from services.cli.settings import cli_settings
from services.runtime.http_client import HttpError

__all__ = ["add_parser"]

_REPO = Path(__file__).resolve().parents[2]
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


@dataclass(frozen=True)
class _Found:
    """The Skydeck the doctor found running at the core URL: the ports it holds, by port."""

    ports: dict[int, str]


def add_parser(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = subparsers.add_parser(
        "doctor", help="check what running Skydeck needs (Python, the core, clocks, ports), then what its tests need"
    )
    p.set_defaults(func=_doctor)


def _doctor(args: argparse.Namespace) -> int:
    found = _Found({})
    running: list[Callable[[], list[Check]]] = [_python, _venv, _packages, _web_ui, lambda: _core_and_clock(found), lambda: _ports(found), _ros2, _camera]
    testing: list[Callable[[], list[Check]]] = [_browser, _test_tools]
    failed = warned = 0
    for title, checks in (("running Skydeck", running), ("running the tests (make test)", testing)):
        print(f"{title}:", flush=True)
        for check in checks:
            for finding in check():
                print(finding.line(), flush=True)
                failed += finding.status == "FAIL"
                warned += finding.status == "warn"
    if failed:
        print(f"{failed} problem(s) to fix before Skydeck can run")
    else:
        print("Skydeck can run" + (f" ({warned} warning(s) above)" if warned else "; all checks passed"))
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


def _web_ui() -> list[Check]:
    swagger = _REPO / "web_ui" / "vendor" / "node_modules" / "swagger-ui-dist"
    if (_REPO / "web_ui").is_dir() and not swagger.is_dir():
        return [Check("warn", "Swagger UI missing: /docs has no page", "run `make install` (npm ci in web_ui/vendor)")]
    return []


def _core_and_clock(found: _Found) -> list[Check]:
    url = core_url()
    try:
        reply = get(url + "/health", timeout_s=3.0)
    except HttpError as error:
        missing = f"core at {url} not reachable ({error})"
        fix = "start it with `skydeck core` or `make up`, or set SKYDECK_CORE_URL to where it runs"
        if "core_url" not in cli_settings().model_fields_set:  # nothing says one should run yet
            return [Check("warn", f"no core running: {missing}", fix)]
        return [Check("FAIL", missing, fix)]
    if reply.status != 200:
        return [Check("FAIL", f"core at {url} answered {reply.status} to /health", "is another server on that port?")]
    health = reply.json() if reply.headers.get("content-type", "").startswith("application/json") else {}
    found.ports.update(_held_by(url, health))
    found_nodes = [Check("ok", f"core at {url} answers ({health.get('nodes', '?')} node(s) registered)")]
    served = reply.headers.get("date")
    if served:
        skew = abs(email.utils.parsedate_to_datetime(served).timestamp() - time.time())
        if skew > _MAX_SKEW_S:
            found_nodes.append(
                Check("warn", f"clock skew with the core: {skew:.1f} s", "sync both machines' clocks (NTP): stamps and delays compare them")
            )
        else:
            found_nodes.append(Check("ok", f"clock skew with the core under {_MAX_SKEW_S:g} s"))
    return found_nodes


def _held_by(url: str, health: dict[str, Any]) -> dict[int, str]:
    """The ports of this machine the Skydeck at ``url`` holds: its core's, its endpoints', and
    those of its nodes (from its graph)."""
    parts = urllib.parse.urlsplit(url)
    if parts.hostname not in ("127.0.0.1", "localhost", "::1"):
        return {}
    held = {parts.port or 80: "core"}
    endpoints = health.get("endpoints")
    if isinstance(endpoints, dict):
        held.update({port: name for name, port in endpoints.items() if isinstance(port, int)})
    try:
        graph = get(url + "/api/graph", timeout_s=3.0).json()
    except (HttpError, ValueError):
        return held
    for node in graph.get("nodes", []) if isinstance(graph, dict) else []:
        node_url = urllib.parse.urlsplit(str(node.get("url", "")))
        if node_url.hostname in ("127.0.0.1", "localhost", "::1") and node_url.port:
            held.setdefault(node_url.port, str(node.get("name", "a node")).lstrip("/"))
    return held


def _default_ports() -> dict[int, str]:
    """The ports `skydeck launch` takes: the workshop's processes and the core's endpoints
    (from the launch plan and the table of endpoints), on the base port of the core URL when it
    is this machine's (the default 8000 otherwise)."""
    from services.launch.errors import LaunchError
    from services.launch.plan import DEFAULT_BASE_PORT, LaunchOptions, plan_launch
    from services.launch.spec import default_launch_file, load_launch_file

    parts = urllib.parse.urlsplit(core_url())
    local = parts.hostname in ("127.0.0.1", "localhost", "::1")
    options = LaunchOptions(seed=0, base_port=parts.port if local and parts.port else DEFAULT_BASE_PORT)
    try:
        ports = {plan.port: plan.name for plan in plan_launch(load_launch_file(default_launch_file(), {}), options)}
    except LaunchError:  # a core so high a launch on its port could not start: the core's alone
        return {options.base_port: "core"}
    ports.update({port: endpoint.name for endpoint, port in options.core_endpoints().items() if port})
    return ports


def _ports(found: _Found) -> list[Check]:
    from services.runtime.ports import port_is_free

    defaults = _default_ports()
    taken = {port: role for port, role in defaults.items() if not port_is_free(port)}
    ours = {port: role for port, role in taken.items() if port in found.ports}
    others = {port: role for port, role in taken.items() if port not in found.ports}
    findings = []
    if ours:
        held = ", ".join(f"{port} ({found.ports[port]})" for port in ours)
        findings.append(Check("ok", f"ports held by the Skydeck found at {core_url()}: {held}"))
    if others:
        findings.append(
            Check(
                "warn",
                f"ports in use by something else: {', '.join(f'{port} ({role})' for port, role in others.items())}",
                "stop what holds them, or run Skydeck beside it with `skydeck launch --base-port N` "
                "(its protocol endpoints move with it)",
            )
        )
    free = [port for port in defaults if port not in taken]
    if free and not others:
        findings.append(Check("ok", "default ports free: " + ", ".join(str(port) for port in free)))
    return findings


def _browser() -> list[Check]:
    found: list[Check] = []
    chromium = _CHROMIUM if _CHROMIUM.exists() else (Path(p) if (p := shutil.which("chromium")) else None)
    if chromium is None:
        found.append(Check("warn", "no Chromium for the browser tests", "apt-get install chromium (Debian's; `make test` does it as root)"))
    else:
        found.append(Check("ok", f"Chromium at {chromium}"))
    if importlib.util.find_spec("playwright") is None:
        found.append(Check("warn", "Playwright is not installed (browser tests)", "run `make install` (it is in requirements.lock)"))
    else:
        found.append(Check("ok", "Playwright installed"))
    return found


def _test_tools() -> list[Check]:
    found: list[Check] = []
    if shutil.which("docker-compose") is None:
        found.append(Check("warn", "no docker-compose for the container tests", "`make test-deps` installs Debian's package"))
    else:
        found.append(Check("ok", "docker-compose installed"))
    clients = _REPO / "tests" / "clients"
    if clients.is_dir():
        if shutil.which("node") is None:
            found.append(Check("warn", "no Node.js for the roslibjs and Foxglove client tests", "apt-get install nodejs npm"))
        elif not (clients / "node_modules").is_dir():
            found.append(Check("warn", "the protocol clients' packages are missing", "run `make install` (npm ci in tests/clients)"))
        else:
            found.append(Check("ok", "Node.js and the protocol clients' packages installed"))
    return found


def _ros2() -> list[Check]:
    """The ROS 2 bridge's extra, and the domain a running bridge joined (its module says)."""
    from services.protocols.ros2.extra import doctor_findings

    try:
        graph = get(core_url() + "/api/graph", timeout_s=3.0).json()
    except (HttpError, ValueError):
        graph = None
    return [Check(*finding) for finding in doctor_findings(graph)]


def _camera() -> list[Check]:
    from sim_server.camera import opengl_status  # PyBullet and OpenGL: loaded for this check only

    why = opengl_status()
    if why is None:
        return [Check("ok", "the simulator's camera renders with OpenGL (EGL)")]
    return [Check("warn", f"the simulator's camera falls back to PyBullet's renderer (slow: 7-10 frames/s at 640x480): {why}",
                  "apt-get install libegl1 libgl1-mesa-dri")]  # fmt: skip
