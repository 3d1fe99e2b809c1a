"""``skydeck launch FILE``: which launch file, read how, and the supervisor that runs it.

    exit_code = run_launch("path/to/ros_workshop/launch/nodes.launch", LaunchOptions(base_port=8000))

A YAML launch file (:mod:`services.launch.spec`) lists every process, the core included. A
roslaunch XML file (:mod:`services.launch.roslaunch`) lists nodes and parameters only. Either
way the launch first looks for a running core, as roslaunch looks at ``ROS_MASTER_URI``: at
``SKYDECK_CORE_URL`` if it is set (and ``--base-port`` is not given), else at the launch's own
core URL (``--base-port``); a local ``SKYDECK_CORE_URL``'s port is then the base port. If a core
answers there, the launch's nodes join it and no core is started (so a roslaunch file runs
beside ``skydeck launch --exclude perception,control,ai``); if none does, the launch starts its
core there, unless the URL is another machine's (as roslaunch starts no roscore for a remote
master: one line says so). Both go to the same :class:`~services.launch.supervisor.Supervisor`.
"""

from __future__ import annotations

import asyncio
import dataclasses
import urllib.parse
from collections.abc import Mapping
from pathlib import Path
from typing import TextIO

from services.launch.arguments import LaunchArgument
from services.launch.errors import LaunchError
from services.launch.output import say
from services.launch.plan import LaunchOptions, core_url
from services.launch.ros2 import (
    declared_ros2_arguments,
    find_launch_file_in_package,
    load_ros2_launch,
    ros2_kind,
    workspace_for,
)
from services.launch.ros2.model import Ros2Launch
from services.launch.roslaunch import RosLaunch, is_roslaunch_file
from services.launch.roslaunch_reader import load_roslaunch_file
from services.launch.roslaunch_xml import declared_arguments
from services.launch.settings import LaunchSettings
from services.launch.spec import LaunchSpec, find_launch_file, load_launch_file
from services.launch.supervisor import Supervisor
from services.runtime.http_client import HttpError, request_once

__all__ = ["core_answers", "launch_arguments", "package_launch_file", "run_launch"]

_CORE_PROBE_S = 1.0
_THIS_MACHINE = ("127.0.0.1", "localhost", "::1", "0.0.0.0")


def run_launch(
    path: str | Path | None = None,
    options: LaunchOptions | None = None,
    *,
    out: TextIO | None = None,
    launch_args: Mapping[str, str] | None = None,
    settings: LaunchSettings | None = None,
    base_port_given: bool = True,
) -> int:
    """``skydeck launch``: load the launch file (default: the workshop's; a bare name such as
    ``robot`` names a shipped one; a ``.launch``/``.xml`` file is roslaunch XML; a ``.py`` file,
    ROS 2 XML or YAML with ``launch:`` is ROS 2's, :mod:`services.launch.ros2`), with
    ``launch_args`` as its ``name:=value`` arguments, and run it until stopped.

    A running core is used, and none started, when one answers where the launch looks (see the
    module docstring: ``SKYDECK_CORE_URL`` in ``settings`` unless ``base_port_given``); the
    launch's own control node comes with a core it starts. Raises ``LaunchError``
    (``LaunchFileError`` for the file) with one line.
    """
    file = find_launch_file(path)
    options = options or LaunchOptions()
    settings = settings or LaunchSettings()
    ros2 = ros2_kind(file) is not None
    roslaunch = not ros2 and is_roslaunch_file(file)
    if ros2 or roslaunch:
        if ros2:
            ros: RosLaunch | Ros2Launch = load_ros2_launch(file, launch_args, environ=settings.environment)
        else:
            ros = load_roslaunch_file(file, launch_args, environ=settings.environment)
        for warning in ros.warnings:
            say(out, f"warning: {warning}")
        spec, parameters = ros.spec(start_core=True), ros.parameters
    else:
        spec, parameters = load_launch_file(file, launch_args or {}), ()
    looked_at = settings.core_url.rstrip("/") if settings.core_url_given and not base_port_given else None
    if looked_at is not None and _this_machine(looked_at):  # its port is the base port
        options = dataclasses.replace(options, base_port=_base_port_at(looked_at, spec))
    url = looked_at or core_url(spec, options)
    running = core_answers(url)
    if running:
        say(out, f"a core answers at {url}: the launch joins it")
        if ros2 or roslaunch:
            spec = ros.spec(start_core=False)
        else:
            options = _without_core(spec, options, url)
    elif looked_at is not None and not _this_machine(looked_at):
        raise LaunchError(
            f"no core answers at SKYDECK_CORE_URL={looked_at}, which is not this machine: start the core "
            "there, or unset SKYDECK_CORE_URL (or give --base-port) to start one here"
        )
    supervisor = Supervisor(
        spec, options, out=out, control=not running, parameters=parameters, settings=settings,
        core_url=url if running else None,
    )  # fmt: skip
    return asyncio.run(supervisor.run())


def _without_core(spec: LaunchSpec, options: LaunchOptions, url: str) -> LaunchOptions:
    """``options`` leaving out the launch file's core (one already answers at ``url``)."""
    cores = tuple(node.name for node in spec.nodes if node.is_core)
    if len(cores) == len(spec.nodes):
        raise LaunchError(f"a core already answers at {url}, and the launch file starts nothing else")
    return dataclasses.replace(options, exclude=(*options.exclude, *cores))


def _this_machine(url: str) -> bool:
    parts = urllib.parse.urlsplit(url)
    return parts.scheme == "http" and parts.hostname in _THIS_MACHINE


def _base_port_at(url: str, spec: LaunchSpec) -> int:
    """The base port that puts the launch's core at ``url`` (a local ``SKYDECK_CORE_URL``)."""
    offset = next((node.port_offset for node in spec.nodes if node.is_core), 0)
    port = urllib.parse.urlsplit(url).port or 80
    if port - offset < 1:
        raise LaunchError(f"SKYDECK_CORE_URL={url}: the launch's core cannot be on port {port} (its base port would be below 1)")
    return port - offset


def launch_arguments(path: str | Path | None = None) -> dict[str, LaunchArgument]:
    """The arguments the launch file takes as ``name:=value`` (``skydeck launch FILE
    --show-args``), in the order it declares them: a YAML file's ``arguments:``, a roslaunch
    file's settable ``<arg>``s. Raises ``LaunchFileError`` as loading it does."""
    file = find_launch_file(path)
    if ros2_kind(file) is not None:
        return declared_ros2_arguments(file, environ=LaunchSettings().environment)
    if is_roslaunch_file(file):
        return declared_arguments(file)
    return dict(load_launch_file(file).arguments)


def package_launch_file(package: str, name: str) -> Path:
    """``skydeck launch PACKAGE FILE`` (``ros2 launch``): the file in the package's launch
    folder, the package found in the current folder's workspace. Raises ``LaunchError``."""
    return find_launch_file_in_package(workspace_for(None), package, name)


def core_answers(url: str) -> bool:
    """Whether a Skydeck core answers at ``url`` (a roslaunch file then uses it, as roslaunch
    uses a running roscore)."""
    try:
        reply = request_once("GET", f"{url}/health", timeout_s=_CORE_PROBE_S)
        return reply.status == 200 and bool(reply.json().get("node") == "/skydeck_core")
    except (HttpError, ValueError, AttributeError):  # no core, or something else answering there
        return False
