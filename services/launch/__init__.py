"""``skydeck launch`` (roslaunch): launch files, and the supervisor that runs them.

    from services.launch import LaunchOptions, run_launch
    exit_code = run_launch("my_launch.yaml", LaunchOptions(base_port=9000, exclude=("ai",)))

Errors: ``LaunchError`` (a launch cannot go ahead), and its subclass ``LaunchFileError`` (the
launch file is missing or wrong); both carry one line for the user.
"""

from services.launch.arguments import LaunchArgument, show_arguments
from services.launch.errors import LaunchError, LaunchFileError
from services.launch.launched import NodeState, NodeStatus
from services.launch.plan import (
    DEFAULT_BASE_PORT,
    LaunchOptions,
    NodePlan,
    core_url,
    default_command,
    plan_launch,
)
from services.launch.roslaunch import RosLaunch, RosNode, is_roslaunch_file
from services.launch.roslaunch_reader import load_roslaunch_file
from services.launch.run import core_answers, launch_arguments, package_launch_file, run_launch
from services.launch.spec import (
    BUILTIN_RUNS,
    PLACEHOLDERS,
    LaunchSpec,
    NodeSpec,
    default_launch_file,
    find_launch_file,
    load_launch_file,
    shipped_launch_files,
)
from services.launch.supervisor import CommandFor, Supervisor

__all__ = [
    "BUILTIN_RUNS",
    "DEFAULT_BASE_PORT",
    "PLACEHOLDERS",
    "CommandFor",
    "LaunchArgument",
    "LaunchError",
    "LaunchFileError",
    "LaunchOptions",
    "LaunchSpec",
    "NodePlan",
    "NodeSpec",
    "NodeState",
    "NodeStatus",
    "RosLaunch",
    "RosNode",
    "Supervisor",
    "core_answers",
    "core_url",
    "default_command",
    "default_launch_file",
    "find_launch_file",
    "is_roslaunch_file",
    "launch_arguments",
    "load_launch_file",
    "load_roslaunch_file",
    "package_launch_file",
    "plan_launch",
    "run_launch",
    "shipped_launch_files",
    "show_arguments",
]
