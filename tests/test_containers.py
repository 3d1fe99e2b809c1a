"""The container files: docker-compose.yml, docker-compose.robot.yml, the Dockerfile and
requirements-runtime.lock.

No Docker engine runs here, so the compose files are made correct by construction: the
distribution's ``docker-compose config`` validates and resolves both documented commands (the
drone workshop, and the robot world with docker-compose.robot.yml beside it; no engine needed),
and these tests check their structure and that every service's command is one the real CLI, and
the node it runs, accept. tests/test_containers_run.py runs those commands as the containers would.
"""

from __future__ import annotations

import argparse
import importlib
import re
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path
from typing import Any

import pytest
import yaml

from services.builtin_nodes import BUILTIN_NODES
from services.cli.main import build_parser
from services.launch.plan import LaunchOptions, plan_launch
from services.launch.spec import find_launch_file, load_launch_file
from services.protocols.core_process import bind_endpoints
from services.protocols.endpoints import ENDPOINTS
from services.protocols.settings import CoreProcessSettings
from services.runtime.ports import free_port_block
from sim_server.robot.settings import RobotSettings
from sim_server.settings import SimSettings
from tests.compose_config import (
    COMPOSE_FILE,
    DOCKERFILE,
    ROOT,
    VARIANTS,
    container_port,
    health_url,
    published_ports,
    resolve,
    started_services,
)

# The processes and their ports, as in the design's table (and `skydeck launch`).
PORTS = {"core": 8000, "sim": 8001, "perception": 8002, "control": 8003, "ai": 8004}
SIM_TIME_NODES = {"control", "ai"}  # they follow /clock, as in services/launch/workshop.yaml
CORE_URL = "http://core:8000"
# Each compose command runs what a shipped launch file runs.
LAUNCH_FILE = {"drone": "workshop", "robot": "robot"}
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


@pytest.fixture(scope="module", params=list(VARIANTS))
def variant(request: pytest.FixtureRequest) -> str:
    return str(request.param)


@pytest.fixture(scope="module")
def started(variant: str) -> dict[str, dict[str, Any]]:
    """What the variant's ``up`` starts, resolved by the real tool with a token set."""
    return started_services(resolve(variant, env={"SKYDECK_TOKEN": "t0ken"}))


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
    return _parse([_interpolate_defaults(str(word)) for word in command[1:]])


def _interpolate_defaults(value: str) -> str:
    """``${NAME:-default}`` as compose resolves it with NAME unset."""
    return re.sub(r"\$\{\w+:-([^}]*)\}", r"\1", value)


def _flag(command: list[Any], flag: str) -> str | None:
    words = [str(word) for word in command]
    return words[words.index(flag) + 1] if flag in words else None


# -- the compose tool ---------------------------------------------------------------------------


def test_docker_compose_config_accepts_the_file() -> None:
    resolved = resolve("drone")
    assert set(started_services(resolved)) == set(PORTS)
    sim = resolved["services"]["sim"]
    assert sim["environment"]["SKYDECK_SIM_SPEED"] == "1" and _flag(sim["command"], "--boxes") == "8"


def test_environment_reaches_the_services() -> None:
    env = {
        "SKYDECK_TOKEN": "t0ken",
        "SKYDECK_SIM_SPEED": "max",
        "SKYDECK_SIM_SEED": "7",
        "SKYDECK_SIM_BOXES": "3",
    }
    resolved = resolve("drone", env=env)["services"]
    for name, service in resolved.items():
        assert service["environment"]["SKYDECK_TOKEN"] == "t0ken", name
    sim = resolved["sim"]
    assert (sim["environment"]["SKYDECK_SIM_SPEED"], sim["environment"]["SKYDECK_SIM_SEED"]) == ("max", "7")
    assert _flag(sim["command"], "--boxes") == "3"


def test_the_robot_worlds_settings_reach_its_simulator() -> None:
    env = {"SKYDECK_SIM_SPEED": "max", "SKYDECK_SIM_SEED": "7", "SKYDECK_SIM_ROBOTS": "2",
           "SKYDECK_SIM_OBSTACLES": "3", "SKYDECK_SIM_BOXES": "5"}  # fmt: skip
    sim = resolve("robot", env=env)["services"]["sim"]
    assert _flag(sim["command"], "--world") == "robot"
    assert _flag(sim["command"], "--boxes") is None, "the robot world refuses --boxes"
    sim_env = {key: value for key, value in sim["environment"].items() if key.startswith("SKYDECK_SIM_")}
    assert sim_env == {"SKYDECK_SIM_SPEED": "max", "SKYDECK_SIM_SEED": "7", "SKYDECK_SIM_ROBOTS": "2",
                       "SKYDECK_SIM_OBSTACLES": "3"}  # fmt: skip
    settings = {key.removeprefix("SKYDECK_SIM_").lower(): value for key, value in sim_env.items()}
    RobotSettings.model_validate(settings)  # values the robot world takes


# -- both commands, resolved --------------------------------------------------------------------


def test_each_command_starts_what_its_launch_file_starts(
    variant: str, started: dict[str, dict[str, Any]]
) -> None:
    spec = load_launch_file(find_launch_file(LAUNCH_FILE[variant]), {})  # the arguments' defaults
    plans = plan_launch(spec, LaunchOptions(seed=1))
    assert set(started) == {plan.name for plan in plans}, "nor the other world's nodes"
    for plan in plans:
        service = started[plan.name]
        assert container_port(service) == plan.port, plan.name
        assert _flag(service["command"], "--world") == _flag(list(plan.args), "--world"), plan.name
        assert ("--use-sim-time" in service["command"]) is ("--use-sim-time" in plan.args), plan.name
    assert {service["image"] for service in started.values()} == {"skydeck:local"}, "one image"


def test_published_ports_are_the_cores_on_loopback(started: dict[str, dict[str, Any]]) -> None:
    # The core's own, and each protocol endpoint's default port (the table of endpoints).
    expected = {"127.0.0.1:8000:8000", *(f"127.0.0.1:{e.default_port}:{e.default_port}" for e in ENDPOINTS)}
    assert sorted(published_ports(started["core"])) == sorted(expected)  # an override may reorder them
    for name, service in started.items():
        if name != "core":
            assert published_ports(service) == [], f"{name} is reached through the core, not published"


def test_every_started_service_is_healthchecked_after_a_healthy_core(started: dict[str, dict[str, Any]]) -> None:
    for name, service in started.items():
        assert health_url(service) == f"http://127.0.0.1:{container_port(service)}/health", name
        compile(service["healthcheck"]["test"][3], f"{name} healthcheck", "exec")  # valid Python
        assert service["restart"] == "unless-stopped", name
        if name == "core":
            assert "depends_on" not in service
        else:
            assert service["depends_on"] == {"core": {"condition": "service_healthy"}}, name
            args, _ = _command(service)
            assert (args.core_url, args.advertise_url) == (CORE_URL, f"http://{name}:{container_port(service)}")


def test_the_token_reaches_every_started_service(started: dict[str, dict[str, Any]]) -> None:
    # The core's rosbridge and Foxglove endpoints check it in the core's process.
    for name, service in started.items():
        assert service["environment"]["SKYDECK_TOKEN"] == "t0ken", name


def test_the_cores_endpoints_listen_where_the_core_does(started: dict[str, dict[str, Any]]) -> None:
    # Published container ports reach only sockets on the container's every interface: the core's
    # --host (0.0.0.0) must be the endpoints' too. Bound on free ports, and closed, never served.
    args, _ = _command(started["core"])
    base = free_port_block(len(ENDPOINTS))
    ports = {endpoint.setting: base + index for index, endpoint in enumerate(ENDPOINTS)}
    sockets = bind_endpoints(CoreProcessSettings(host=args.host, port=0, **ports))
    try:
        assert {name: sock.getsockname()[0] for name, sock in sockets.items()} == {e.name: "0.0.0.0" for e in ENDPOINTS}
    finally:
        for sock in sockets.values():
            sock.close()


def test_the_robot_simulators_command_is_one_it_accepts(monkeypatch: pytest.MonkeyPatch) -> None:
    sim = resolve("robot")["services"]["sim"]
    args, extra = _command(sim)
    assert (args.command, args.node, args.host) == ("run", "sim", "0.0.0.0")
    _assert_node_accepts("sim", extra, monkeypatch)


def test_the_readme_shows_each_command_on_one_line() -> None:
    readme = (ROOT / "README.md").read_text()
    for files in VARIANTS.values():
        flags = [word for path in files for word in ("-f", path.name)] if len(files) > 1 else []
        command = " ".join(["docker", "compose", *flags, "up"])
        assert re.search(rf"^{re.escape(command)}(\s+#.*)?$", readme, re.MULTILINE), f"README shows `{command}`"


# -- structure ----------------------------------------------------------------------------------


def test_the_five_processes_from_one_image(services: dict[str, dict[str, Any]]) -> None:
    services = {name: service for name, service in services.items() if not service.get("profiles")}
    assert set(services) == set(PORTS)
    assert {service["image"] for service in services.values()} == {"skydeck:local"}
    assert {str(service["build"]) for service in services.values()} == {"."}
    for name, service in services.items():
        assert service["restart"] == "unless-stopped", name


def test_the_ai_keeps_its_progress_in_a_named_volume(
    compose: dict[str, Any], services: dict[str, dict[str, Any]]
) -> None:
    state_dir = re.search(r"SKYDECK_STATE_DIR=(\S+)", DOCKERFILE.read_text())
    assert state_dir is not None, "the Dockerfile sets SKYDECK_STATE_DIR"
    assert services["ai"]["volumes"] == [f"ai-state:{state_dir.group(1)}"]
    assert "ai-state" in compose["volumes"]


# -- commands: what the CLI and the nodes accept --------------------------------------------------


def test_the_ros2_profile_adds_the_bridge_from_an_image_with_the_extra(
    services: dict[str, dict[str, Any]], monkeypatch: pytest.MonkeyPatch
) -> None:
    bridge = services["ros2_bridge"]
    assert bridge["profiles"] == ["ros2"] and bridge["image"] == "skydeck:ros2"
    assert bridge["build"]["args"]["SKYDECK_EXTRAS"] == "ros2"
    assert "ARG SKYDECK_EXTRAS" in DOCKERFILE.read_text()
    args, extra = _command(bridge)
    assert (args.command, args.node, args.port, args.core_url) == ("run", "ros2_bridge", 8005, CORE_URL)
    assert health_url(bridge) == "http://127.0.0.1:8005/health"
    _assert_node_accepts("ros2_bridge", extra, monkeypatch)


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
    assert set(sim_env) == {"SKYDECK_SIM_SPEED", "SKYDECK_SIM_SEED"}  # --boxes is a flag
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
    instructions = "\n".join(line for line in final.splitlines() if not line.lstrip().startswith("#"))
    assert "pip install" not in instructions
    assert re.search(r"-m pip uninstall --yes --quiet pip setuptools wheel", instructions), (
        "the base image's own packaging tools are removed"
    )
    for tool in ("npm", "node", "apt-get", "apk", "g++", "gcc", "build-essential", "make"):
        assert not re.search(rf"(?<![\w-]){re.escape(tool)}(?![\w-])", instructions), (
            f"the final stage does not use {tool}"
        )
    # It takes only the finished venv from the build stage, whose last step removes pip and
    # setuptools from it, and it is the only image: compose runs it for every service.
    assert re.findall(r"^COPY .*$", final, re.MULTILINE) == ["COPY --from=build /opt/skydeck /opt/skydeck"]
    assert "pip uninstall --yes setuptools pip" in text
    assert re.match(r"\nFROM \S+\n", final), "the last stage is the image (no name, no other target)"
    assert "--require-hashes" in text and "requirements-runtime.lock" in text
    assert "swagger-ui-dist" in text, "the core's /docs needs the Swagger UI files"
    assert "three/build" in text, "the dashboard's 3D view needs three.js"


@pytest.mark.slow
@pytest.mark.timeout(180)
def test_the_images_wheel_carries_both_worlds_and_the_endpoints(tmp_path: Path) -> None:
    """The build stage's sources (its ``COPY`` lines from the context), made into a wheel as the
    build stage makes it: every node ``skydeck run`` knows, the endpoints, the shipped launch
    files and every dashboard file (the 3D view's included) are in it."""
    text = DOCKERFILE.read_text()
    build = text[text.index(" AS build") : text.rindex("\nFROM ")]
    source = tmp_path / "src"
    for line in re.findall(r"^COPY (?!--)(.+)$", build, re.MULTILINE):
        *paths, _ = line.split()
        for path in paths:
            if path.startswith("requirements"):
                continue
            origin = ROOT / path
            if origin.is_dir():
                ignore = shutil.ignore_patterns("node_modules", "__pycache__", "*.pyc")  # .dockerignore's
                shutil.copytree(origin, source / path, ignore=ignore)
            else:
                source.mkdir(exist_ok=True)
                shutil.copy2(origin, source / path)
    built = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--no-build-isolation", "-w", str(tmp_path), str(source)],
        capture_output=True, text=True, timeout=150, check=False,
    )  # fmt: skip
    assert built.returncode == 0, built.stderr
    (wheel,) = tmp_path.glob("*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    modules = [*BUILTIN_NODES.values(), "services.core.app", "services.protocols.core_process", "sim_server.robot.node"]
    wanted = {module.replace(".", "/") + ".py" for module in modules}
    wanted |= {f"services/launch/{name}.yaml" for name in LAUNCH_FILE.values()}
    static = ROOT / "web_ui" / "static"
    wanted |= {path.relative_to(ROOT).as_posix() for path in static.rglob("*") if path.is_file()}
    assert wanted - names == set(), "missing from the image's wheel"


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
