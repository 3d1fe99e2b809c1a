"""``skydeck core`` (roscore) and ``skydeck run NODE`` (rosrun): start one process."""

from __future__ import annotations

import argparse
import importlib
import runpy
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from services.builtin_nodes import BUILTIN_NODES
from services.cli.errors import CliError
from shared_models.errors import SkydeckError

if TYPE_CHECKING:
    from services.ros.workspace import Target

__all__ = ["add_parsers"]


def add_parsers(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    core = subparsers.add_parser("core", help="run the core: registry, gateway, dashboard (like roscore)")
    _add_server_flags(core, default_port=8000)
    add_endpoint_flags(core)
    core.add_argument(
        "--class-tokens",
        type=Path,
        metavar="FILE",
        help="run a class: its tokens file (`name,token` lines, `skydeck class` writes it); docs/security.md",
    )
    core.add_argument(
        "--class-rules", type=Path, metavar="FILE", help="the class's rules: what students share (YAML); docs/security.md"
    )
    core.add_argument(
        "--class-gradebook", type=Path, metavar="FILE", help="the grades the class page shows (`skydeck grade --class`'s JSON)"
    )
    core.set_defaults(func=_core)

    run = subparsers.add_parser(
        "run",
        help=f"run one node: a built-in ({', '.join(BUILTIN_NODES)}), a .py file, or PKG EXECUTABLE (like ros2 run)",
        description=(
            "Flags after NODE that `run` does not know are passed to the node (e.g. sim's --seed). "
            "`--ros-args -p NAME:=VALUE --params-file FILE.yaml` set the node's parameters, as in ROS 2. "
            "`skydeck run PKG EXECUTABLE` runs a workspace package's console script (ros2 run) or "
            "script (rosrun)."
        ),
    )
    run.add_argument("node", help=f"{' | '.join(BUILTIN_NODES)} | path/to/node.py | PKG EXECUTABLE")
    run.add_argument(
        "--workspace",
        type=Path,
        action="append",
        metavar="DIR",
        help="a ROS workspace (or folder of packages) to find packages and their msg/srv/action files in "
        "(default: the current folder's src/, and the running file's)",
    )
    _add_server_flags(run, default_port=None)
    run.add_argument("--core-url", help="where the core is (default: SKYDECK_CORE_URL or http://127.0.0.1:8000)")
    run.add_argument("--use-sim-time", action="store_true", help="follow /clock instead of the wall clock")
    run.set_defaults(func=_run)


def _add_server_flags(parser: argparse.ArgumentParser, *, default_port: int | None) -> None:
    parser.add_argument("--host", help="address to listen on (default 127.0.0.1; 0.0.0.0 in containers)")
    parser.add_argument("--port", type=_port, default=default_port, help="port to listen on")
    parser.add_argument("--advertise-url", help="URL other processes reach this one at (containers)")
    parser.add_argument("--log-level", choices=["debug", "info", "warning", "error"], help="default info")


def add_endpoint_flags(parser: argparse.ArgumentParser, *, moved_by: str = "") -> None:
    """A ``--NAME-port`` flag per endpoint of the table (``skydeck core`` and ``skydeck launch``;
    ``moved_by`` says how a launch moves the default)."""
    from services.protocols.endpoints import ENDPOINTS

    for endpoint in ENDPOINTS:
        parser.add_argument(
            endpoint.flag,
            type=_port,
            dest=endpoint.setting,
            help=f"{endpoint.summary} (default {endpoint.default_port}{moved_by}; 0: off)",
        )


def _port(text: str) -> int:
    if not text.isdigit() or not 0 <= int(text) <= 65535:
        raise argparse.ArgumentTypeError(f"expected a port number 0-65535, got {text!r}")
    return int(text)


def _server_flags(args: argparse.Namespace) -> dict[str, object]:
    """The flags every server process takes, as settings (None: not given)."""
    return {"host": args.host, "port": args.port, "advertise_url": args.advertise_url, "log_level": args.log_level}


def _core(args: argparse.Namespace) -> int:
    if args.extra:
        raise CliError(f"unknown option for `skydeck core`: {' '.join(args.extra)}")
    from services.protocols.core_process import serve
    from services.protocols.endpoints import ENDPOINTS
    from services.protocols.settings import CoreProcessSettings

    ports = {endpoint.setting: getattr(args, endpoint.setting) for endpoint in ENDPOINTS}
    classroom = {
        "class_tokens": args.class_tokens, "class_rules": args.class_rules, "class_gradebook": args.class_gradebook,
    }  # fmt: skip
    serve(CoreProcessSettings.from_flags(**_server_flags(args), **ports, **classroom))  # flags over SKYDECK_*
    return 0


def _run(args: argparse.Namespace) -> int:
    from services.cli.student import ask_namespace, fence_namespace, given_namespaces
    from services.runtime.ros_args import (
        parse_ros1_args,
        parse_ros_args,
        set_process_ros_arguments,
        split_ros_args,
    )
    from services.runtime.settings import NodeSettings, use_node_settings

    # This process's settings, flags over SKYDECK_*, built once for every node it makes.
    settings = NodeSettings.from_flags(
        **_server_flags(args), core_url=args.core_url, use_sim_time=True if args.use_sim_time else None
    )
    use_node_settings(settings)
    node_argv, ros_argv = split_ros_args(list(args.extra))
    arguments = parse_ros_args(ros_argv)
    if args.node not in BUILTIN_NODES:  # a ROS 1 program's `chatter:=/news _rate:=5` too
        arguments = parse_ros1_args(node_argv)[1] + arguments
    namespace = ask_namespace(settings.core_url, settings.token)  # a student's token: their namespace
    if namespace is not None:
        arguments = fence_namespace(namespace, arguments, given_namespaces(arguments, node_argv, settings.ros_namespace))
    set_process_ros_arguments(arguments)  # every node of this process reads them
    if args.node in BUILTIN_NODES:
        module = importlib.import_module(BUILTIN_NODES[args.node])
        return int(module.main(node_argv) or 0)
    from services.ros.workspace import file_target, package_target, workspace_of
    from shared_models.definitions.index import use_workspace

    path = Path(args.node)
    for folder in args.workspace or []:
        if not folder.is_dir():
            raise CliError(f"--workspace {folder}: no such folder")
        use_workspace(folder)
    if path.suffix == ".py":
        if not path.is_file():
            raise CliError(f"no such node file: {path}")
        if (workspace := workspace_of(path)) is not None:
            use_workspace(workspace)  # its siblings' msg/srv/action files
        use_workspace(Path.cwd())
        return _run_program(file_target(path), list(args.extra))
    use_workspace(Path.cwd())
    if not args.extra or args.extra[0].startswith("-"):
        raise CliError(
            f"unknown node {args.node!r}: a built-in ({', '.join(BUILTIN_NODES)}), a path to a .py "
            "file, or a workspace package and its executable (`skydeck run PKG EXECUTABLE`)"
        )
    executable, *argv = args.extra
    return _run_program(package_target(args.node, executable), argv)


def _run_program(target: Target, argv: list[str]) -> int:
    """Run a node program as ``python3 FILE`` (or ``ros2 run``) would, with ROS's module names
    importable (``import rclpy``, ``from geometry_msgs.msg import Twist``: docs/ros.md): a plain
    file as ``__main__``, a file of a Python package as its module (relative imports work), an
    entry point by calling its function."""
    from services.ros import enable_ros_imports

    enable_ros_imports()
    sys.argv = [target.argv0, *argv]  # with --ros-args, as ROS hands them to the program
    sys.path.insert(0, str(target.import_root))
    if target.file is not None and target.file.parent != target.import_root:
        sys.path.insert(1, str(target.file.parent))  # `import helpers` beside it, as python3 FILE
    try:
        if target.function is not None and target.module is not None:
            return _exit_status(_entry_point(target.module, target.function)())
        if target.module is not None:
            runpy.run_module(target.module, run_name="__main__", alter_sys=True)
        else:
            runpy.run_path(str(target.file), run_name="__main__")
    except (KeyboardInterrupt, SystemExit, SkydeckError):
        raise  # Ctrl-C, the program's own exit, and Skydeck's one-line errors: main's
    except Exception as error:  # the program's own: its traceback, without Skydeck's frames
        from services.ros.tracebacks import user_traceback

        print(user_traceback(error), file=sys.stderr)
        return 1
    finally:
        _stop_ros_nodes()
    return 0


def _entry_point(module_name: str, function: str):  # type: ignore[no-untyped-def]
    module = importlib.import_module(module_name)
    found = getattr(module, function, None)
    if not callable(found):
        raise CliError(f"{module_name} has no function {function}() (its entry point names {module_name}:{function})")
    return found


def _exit_status(result: object) -> int:
    """What a console script's function returned, as its exit status (``sys.exit(main())``)."""
    if result is None:
        return 0
    if isinstance(result, int):
        return result
    print(result, file=sys.stderr)
    return 1


def _stop_ros_nodes() -> None:
    """The nodes a ROS program left running leave the graph when it ends (or is interrupted)."""
    bridge_module = sys.modules.get("services.ros.bridge")
    if bridge_module is not None:
        bridge_module.bridge.shutdown()
