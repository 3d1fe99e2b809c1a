"""The container files: docker-compose.yml, the Dockerfile and requirements-runtime.lock.

No Docker engine runs here, so the compose file is made correct by construction: the
distribution's ``docker-compose config`` validates it (no engine needed), and these tests check
its structure and that every service's command is one the real CLI, and the node it runs, accept.
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import shutil
import subprocess
import tomllib
from pathlib import Path
from typing import Any

import pytest
import yaml

from services.builtin_nodes import BUILTIN_NODES
from services.cli.main import build_parser
from sim_server.node import SimSettings

ROOT = Path(__file__).resolve().parents[1]
COMPOSE_FILE = ROOT / "docker-compose.yml"
DOCKERFILE = ROOT / "Dockerfile"

# The processes and their ports, as in the design's table (and `skydeck launch`).
PORTS = {"core": 8000, "sim": 8001, "perception": 8002, "control": 8003, "ai": 8004}
SIM_TIME_NODES = {"control", "ai"}  # they follow /clock, as in services/launch/workshop.yaml
CORE_URL = "http://core:8000"
# requirements-runtime.lock is made from pyproject.toml, pinned to requirements.lock.
REGENERATE_RUNTIME_LOCK = (
    ".venv/bin/uv pip compile pyproject.toml -c requirements.lock"
    " --python-version 3.11 --generate-hashes -o requirements-runtime.lock"
)


@pytest.fixture(scope="module")
def compose() -> dict[str, Any]:
    return yaml.safe_load(COMPOSE_FILE.read_text())


@pytest.fixture(scope="module")
def services(compose: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return compose["services"]


def _parse(argv: list[str]) -> tuple[argparse.Namespace, list[str]]:
    """``skydeck ARGV`` through the real parser; argparse errors become test failures."""
    try:
        return build_parser().parse_known_args(argv)
    except SystemExit as error:  # argparse exits on a bad command line
        raise AssertionError(f"`skydeck {' '.join(argv)}` is refused by the CLI") from error


def _command(service: dict[str, Any]) -> tuple[argparse.Namespace, list[str]]:
    command = service["command"]
    assert isinstance(command, list), (
        "commands are exec-form lists: no shell, signals reach skydeck"
    )
    assert command[0] == "skydeck"
    return _parse([str(word) for word in command[1:]])


def _interpolate_defaults(value: str) -> str:
    """``${NAME:-default}`` as compose resolves it with NAME unset."""
    return re.sub(r"\$\{\w+:-([^}]*)\}", r"\1", value)


# -- the compose tool ---------------------------------------------------------------------------


def _docker_compose(
    *args: str, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    tool = shutil.which("docker-compose")
    if tool is None:
        pytest.skip("docker-compose is not installed (`make test-deps` installs Debian's package)")
    return subprocess.run(
        [tool, "-f", str(COMPOSE_FILE), *args],
        cwd=ROOT,
        env={**os.environ, **(env or {})},
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )


def test_docker_compose_config_accepts_the_file() -> None:
    result = _docker_compose("config")
    assert result.returncode == 0, result.stderr
    resolved = yaml.safe_load(result.stdout)
    assert set(resolved["services"]) == set(PORTS)
    sim_env = resolved["services"]["sim"]["environment"]
    assert sim_env["SKYDECK_SIM_SPEED"] == "1" and sim_env["SKYDECK_SIM_BOXES"] == "8"


def test_environment_reaches_the_services() -> None:
    env = {
        "SKYDECK_TOKEN": "t0ken",
        "SKYDECK_SIM_SPEED": "max",
        "SKYDECK_SIM_SEED": "7",
        "SKYDECK_SIM_BOXES": "3",
    }
    result = _docker_compose("config", env=env)
    assert result.returncode == 0, result.stderr
    resolved = yaml.safe_load(result.stdout)["services"]
    for name, service in resolved.items():
        assert service["environment"]["SKYDECK_TOKEN"] == "t0ken", name
    sim_env = resolved["sim"]["environment"]
    assert (
        sim_env["SKYDECK_SIM_SPEED"],
        sim_env["SKYDECK_SIM_SEED"],
        sim_env["SKYDECK_SIM_BOXES"],
    ) == ("max", "7", "3")


# -- structure ----------------------------------------------------------------------------------


def test_the_five_processes_from_one_image(services: dict[str, dict[str, Any]]) -> None:
    assert set(services) == set(PORTS)
    assert {service["image"] for service in services.values()} == {"skydeck:local"}
    assert {str(service["build"]) for service in services.values()} == {"."}
    for name, service in services.items():
        assert service["restart"] == "unless-stopped", name


def test_only_the_core_ports_are_published(services: dict[str, dict[str, Any]]) -> None:
    # The core's own, and its rosbridge and Foxglove endpoints (CoreSettings' defaults).
    assert services["core"]["ports"] == ["127.0.0.1:8000:8000", "127.0.0.1:9090:9090", "127.0.0.1:8765:8765"]
    for name, service in services.items():
        if name != "core":
            assert "ports" not in service, f"{name} is reached through the core, not published"


def test_every_service_checks_its_own_health(services: dict[str, dict[str, Any]]) -> None:
    for name, service in services.items():
        test = service["healthcheck"]["test"]
        assert test[:3] == ["CMD", "python", "-c"], name
        assert f"'http://127.0.0.1:{PORTS[name]}/health'" in test[3], name
        compile(test[3], f"{name} healthcheck", "exec")  # it is valid Python


def test_nodes_wait_for_a_healthy_core(services: dict[str, dict[str, Any]]) -> None:
    assert "depends_on" not in services["core"]
    for name, service in services.items():
        if name != "core":
            assert service["depends_on"] == {"core": {"condition": "service_healthy"}}, name


def test_the_token_is_passed_to_every_service(services: dict[str, dict[str, Any]]) -> None:
    for name, service in services.items():
        assert service["environment"]["SKYDECK_TOKEN"] == "${SKYDECK_TOKEN:-}", name


def test_the_ai_keeps_its_progress_in_a_named_volume(
    compose: dict[str, Any], services: dict[str, dict[str, Any]]
) -> None:
    state_dir = re.search(r"SKYDECK_STATE_DIR=(\S+)", DOCKERFILE.read_text())
    assert state_dir is not None, "the Dockerfile sets SKYDECK_STATE_DIR"
    assert services["ai"]["volumes"] == [f"ai-state:{state_dir.group(1)}"]
    assert "ai-state" in compose["volumes"]


# -- commands: what the CLI and the nodes accept --------------------------------------------------


def test_core_command(services: dict[str, dict[str, Any]]) -> None:
    args, extra = _command(services["core"])
    assert args.command == "core"
    assert extra == [], "`skydeck core` refuses options it does not know"
    assert (args.host, args.port, args.advertise_url) == ("0.0.0.0", 8000, CORE_URL)


@pytest.mark.parametrize("name", ["sim", "perception", "control", "ai"])
def test_node_command(
    services: dict[str, dict[str, Any]], name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    args, extra = _command(services[name])
    assert args.command == "run"
    assert args.node == name and name in BUILTIN_NODES
    assert (args.host, args.port) == ("0.0.0.0", PORTS[name])
    assert args.advertise_url == f"http://{name}:{PORTS[name]}", "others reach it by service name"
    assert args.core_url == CORE_URL
    assert args.use_sim_time is (name in SIM_TIME_NODES)
    _assert_node_accepts(name, extra, monkeypatch)


class _Parsed(Exception):
    """Raised instead of starting the node once its own parser accepted the arguments."""


def _assert_node_accepts(name: str, node_argv: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """The node's ``main`` parses ``node_argv`` with its own parser, then stops before starting."""
    original = argparse.ArgumentParser.parse_args

    def parse_then_stop(
        self: argparse.ArgumentParser, *args: Any, **kwargs: Any
    ) -> argparse.Namespace:
        original(self, *args, **kwargs)  # exits with status 2 on arguments the node does not know
        raise _Parsed

    monkeypatch.setattr(argparse.ArgumentParser, "parse_args", parse_then_stop)
    main = importlib.import_module(BUILTIN_NODES[name]).main
    with pytest.raises(_Parsed):
        try:
            main(node_argv)
        except SystemExit as error:
            raise AssertionError(f"`skydeck run {name}` refuses {node_argv}") from error


def test_sim_options_are_ones_the_simulator_reads(services: dict[str, dict[str, Any]]) -> None:
    sim_env = {
        key: value
        for key, value in services["sim"]["environment"].items()
        if key.startswith("SKYDECK_SIM_")
    }
    assert set(sim_env) == {"SKYDECK_SIM_SPEED", "SKYDECK_SIM_SEED", "SKYDECK_SIM_BOXES"}
    fields = {key.removeprefix("SKYDECK_SIM_").lower(): value for key, value in sim_env.items()}
    assert set(fields) <= set(SimSettings.model_fields)
    # The defaults are valid settings; an unset seed (null: passed on only when set) draws one.
    defaults = {
        key: _interpolate_defaults(value) for key, value in fields.items() if value is not None
    }
    SimSettings.model_validate(defaults)


# -- the image ------------------------------------------------------------------------------------


def test_the_final_stage_runs_as_a_user_without_build_tools() -> None:
    text = DOCKERFILE.read_text()
    final = text[text.rindex("\nFROM ") :]
    assert re.search(r"^USER (?!root\b)\S+", final, re.MULTILINE), "runs as a non-root user"
    for tool in ("npm", "apt-get", "pip install", "g++"):
        assert tool not in final, f"the final stage does not use {tool}"
    assert "--require-hashes" in text and "requirements-runtime.lock" in text
    assert "swagger-ui-dist" in text, "the core's /docs needs the Swagger UI files"
    assert "three/build" in text, "the dashboard's 3D view needs three.js"


def _pins(lock: Path) -> dict[str, tuple[str, frozenset[str]]]:
    """``name -> (version, hashes)`` of a pip-compile style lock."""
    pins: dict[str, tuple[str, frozenset[str]]] = {}
    for block in re.split(r"\n(?=[A-Za-z0-9])", lock.read_text()):
        match = re.match(r"([A-Za-z0-9._-]+)==(\S+)", block)
        if match:
            name = re.sub(r"[-_.]+", "-", match.group(1)).lower()
            pins[name] = (match.group(2), frozenset(re.findall(r"--hash=(\S+)", block)))
    return pins


def test_the_runtime_lock_is_a_subset_of_the_lock() -> None:
    runtime = _pins(ROOT / "requirements-runtime.lock")
    full = _pins(ROOT / "requirements.lock")
    assert runtime, "requirements-runtime.lock has pins"
    for name, pin in runtime.items():
        assert name in full, f"{name} is in requirements-runtime.lock but not in requirements.lock"
        assert pin == full[name], (
            f"{name}: requirements-runtime.lock differs from requirements.lock; regenerate: {REGENERATE_RUNTIME_LOCK}"
        )
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    for requirement in project["dependencies"]:
        name = re.sub(r"[-_.]+", "-", re.match(r"[A-Za-z0-9._-]+", requirement).group(0)).lower()  # type: ignore[union-attr]
        assert name in runtime, f"{name} (pyproject.toml) is missing from requirements-runtime.lock"
    assert "numpy" in runtime, "pybullet imports numpy: it must be a runtime dependency"
    for dev_tool in ("pytest", "playwright", "mypy", "setuptools"):
        assert dev_tool not in runtime, f"{dev_tool} is a dev tool, not a runtime dependency"
