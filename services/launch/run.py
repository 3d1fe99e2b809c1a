"""``skydeck launch FILE``: which launch file, read how, and the supervisor that runs it.

    exit_code = run_launch("path/to/ros_workshop/launch/nodes.launch", LaunchOptions(base_port=8000))

A YAML launch file (:mod:`services.launch.spec`) lists every process, the core included. A
roslaunch XML file (:mod:`services.launch.roslaunch`) lists nodes and parameters only; the core
is started for it only when none answers at the launch's core URL, as roslaunch starts roscore
only when none runs, so it can run beside ``skydeck launch --exclude perception,control,ai``.
Both go to the same :class:`~services.launch.supervisor.Supervisor`.
"""

from __future__ import annotations

import asyncio
import contextlib
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import TextIO

from services.launch.arguments import LaunchArgument
from services.launch.plan import LaunchOptions
from services.launch.roslaunch import is_roslaunch_file
from services.launch.roslaunch_reader import load_roslaunch_file
from services.launch.roslaunch_xml import declared_arguments
from services.launch.spec import find_launch_file, load_launch_file
from services.launch.supervisor import Supervisor
from services.runtime.http_client import HttpError, request_once

__all__ = ["core_answers", "launch_arguments", "run_launch"]

_CORE_PROBE_S = 1.0


def run_launch(
    path: str | Path | None = None,
    options: LaunchOptions | None = None,
    *,
    out: TextIO | None = None,
    launch_args: Mapping[str, str] | None = None,
) -> int:
    """``skydeck launch``: load the launch file (default: the workshop's; a bare name such as
    ``robot`` names a shipped one; a ``.launch``/``.xml`` file is roslaunch XML), with
    ``launch_args`` as its ``name:=value`` arguments, and run it until stopped.

    A roslaunch file starts the core only when none answers at the launch's core URL, as
    roslaunch starts roscore only when none runs; the launch's own control node comes with a
    core it starts. Raises ``LaunchError`` (``LaunchFileError`` for the file) with one line.
    """
    file = find_launch_file(path)
    options = options or LaunchOptions()
    if is_roslaunch_file(file):
        ros = load_roslaunch_file(file, launch_args)
        for warning in ros.warnings:
            _print(out, f"[launch] warning: {warning}")
        start_core = not core_answers(f"http://127.0.0.1:{options.base_port}")
        spec, parameters = ros.spec(start_core=start_core), ros.parameters
    else:
        spec, parameters = load_launch_file(file, launch_args or {}), ()
        start_core = True
    supervisor = Supervisor(spec, options, out=out, control=start_core, parameters=parameters)
    return asyncio.run(supervisor.run())


def launch_arguments(path: str | Path | None = None) -> dict[str, LaunchArgument]:
    """The arguments the launch file takes as ``name:=value`` (``skydeck launch FILE
    --show-args``), in the order it declares them: a YAML file's ``arguments:``, a roslaunch
    file's settable ``<arg>``s. Raises ``LaunchFileError`` as loading it does."""
    file = find_launch_file(path)
    if is_roslaunch_file(file):
        return declared_arguments(file)
    return dict(load_launch_file(file).arguments)


def core_answers(url: str) -> bool:
    """Whether a Skydeck core answers at ``url`` (a roslaunch file then uses it, as roslaunch
    uses a running roscore)."""
    try:
        reply = request_once("GET", f"{url}/health", timeout_s=_CORE_PROBE_S)
        return reply.status == 200 and bool(reply.json().get("node") == "/skydeck_core")
    except (HttpError, ValueError, AttributeError):  # no core, or something else answering there
        return False


def _print(out: TextIO | None, line: str) -> None:
    stream = out or sys.stdout
    with contextlib.suppress(OSError, ValueError):
        stream.write(line + "\n")
        stream.flush()
