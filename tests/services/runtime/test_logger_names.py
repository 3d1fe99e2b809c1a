"""Log lines named as ROS prints them: `[INFO] [talker]: ...`, not the Python logger's name."""

from __future__ import annotations

import logging
import subprocess
import sys
import textwrap
from pathlib import Path

from services.runtime.logger import RosLogFormatter, ros_logger_name

REPO = Path(__file__).resolve().parents[3]


def test_a_node_s_logger_is_named_as_rclpy_names_it() -> None:
    assert ros_logger_name("skydeck.node.talker") == "talker"
    assert ros_logger_name("skydeck.node.robot1/wall_follower") == "robot1.wall_follower"
    assert ros_logger_name("skydeck.node.talker.child") == "talker.child"  # rclpy's get_child
    assert ros_logger_name("uvicorn.error") == "uvicorn.error"  # not a node's: its own name
    assert ros_logger_name("skydeck.nodes") == "skydeck.nodes"


def test_the_line_is_ros_2_s_console_line() -> None:
    record = logging.LogRecord("skydeck.node.talker", logging.WARNING, __file__, 1, "low %s", ("battery",), None)
    assert RosLogFormatter().format(record) == "[WARNING] [talker]: low battery"


def test_every_kind_of_node_prints_its_ros_name_on_stderr() -> None:
    program = textwrap.dedent(
        """
        from services.runtime.executor import configure_logging
        from services.runtime.logger import NodeLogger
        from services.ros.rclpy.logging import RcutilsLogger
        from shared_models.builtin_interfaces import Time

        configure_logging()
        NodeLogger("/robot1/talker", Time, lambda msg: None).info("hello %d", 1)
        RcutilsLogger("listener").get_child("part").warning("careful")
        """
    )
    done = subprocess.run([sys.executable, "-c", program], cwd=REPO, capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines() == ["[INFO] [robot1.talker]: hello 1", "[WARNING] [listener.part]: careful"]
