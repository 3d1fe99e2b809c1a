"""The two compose commands' configurations, as the real ``docker-compose config`` resolves them.

    docker compose up                                                     # the drone workshop
    docker compose -f docker-compose.yml -f docker-compose.robot.yml up   # the robot world

Shared by tests/test_containers.py (structure) and tests/test_containers_run.py (each service's
command run as its container would run it). No Docker engine is needed: ``config`` only reads.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest
import yaml

__all__ = [
    "COMPOSE_FILE",
    "DOCKERFILE",
    "ROBOT_FILE",
    "ROOT",
    "VARIANTS",
    "container_port",
    "docker_compose",
    "health_url",
    "published_ports",
    "resolve",
    "started_services",
]

ROOT = Path(__file__).resolve().parents[1]
COMPOSE_FILE = ROOT / "docker-compose.yml"
ROBOT_FILE = ROOT / "docker-compose.robot.yml"
DOCKERFILE = ROOT / "Dockerfile"

# Each documented command's compose files, in the order its -f flags give them.
VARIANTS = {"drone": (COMPOSE_FILE,), "robot": (COMPOSE_FILE, ROBOT_FILE)}


def docker_compose(
    files: tuple[Path, ...], *args: str, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """The real ``docker-compose -f FILE ... ARGS`` (skips the test when it is not installed)."""
    tool = shutil.which("docker-compose")
    if tool is None:
        pytest.skip("docker-compose is not installed (`make test-deps` installs Debian's package)")
    flags = [word for path in files for word in ("-f", str(path))]
    return subprocess.run(
        [tool, *flags, *args],
        cwd=ROOT,
        env={**os.environ, **(env or {})},
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )


def resolve(variant: str, env: dict[str, str] | None = None) -> dict[str, Any]:
    """The variant's configuration as ``docker-compose config`` prints it, parsed."""
    result = docker_compose(VARIANTS[variant], "config", env=env)
    assert result.returncode == 0, f"docker-compose config ({variant}): {result.stderr}"
    config: dict[str, Any] = yaml.safe_load(result.stdout)
    return config


def started_services(config: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """The services ``up`` starts when no profile is asked for: those without ``profiles``
    (the compose specification's rule; v1's ``config`` prints the others too, v2's leaves them out)."""
    return {name: service for name, service in config["services"].items() if not service.get("profiles")}


def published_ports(service: dict[str, Any]) -> list[str]:
    """``HOST_IP:PUBLISHED:TARGET`` for each published port, from either tool's resolved form
    (v1: ``127.0.0.1:8000:8000/tcp``; v2: a mapping with ``host_ip``, ``published``, ``target``)."""
    ports = []
    for port in service.get("ports", []):
        if isinstance(port, dict):
            ports.append(f"{port.get('host_ip', '')}:{port['published']}:{port['target']}")
        else:
            ports.append(str(port).removesuffix("/tcp"))
    return ports


def container_port(service: dict[str, Any]) -> int:
    """The port the service's process listens on inside its container (its ``--port``)."""
    command = [str(word) for word in service["command"]]
    return int(command[command.index("--port") + 1])


def health_url(service: dict[str, Any]) -> str:
    """The URL the service's healthcheck command opens."""
    test = service["healthcheck"]["test"]
    assert test[:3] == ["CMD", "python", "-c"], "healthchecks are exec-form Python one-liners"
    match = re.search(r"'(http://[^']+)'", test[3])
    assert match is not None, f"the healthcheck opens no URL: {test[3]}"
    return match.group(1)
