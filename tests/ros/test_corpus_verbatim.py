"""The seeds' own code blocks are in the corpus verbatim (nothing reformatted them).

The ROS 2 seed's blocks are whole files. The ROS 1 seed's are fragments a student pastes into
the workshop's files: each is there line for line, at the indentation it was pasted at (a
block that goes inside the main loop is indented by the loop), trailing spaces and tabs kept.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.ros.conftest import CORPUS

SEED = Path("/work/shared/seeds/001_e6c1d12a3b8a3e88.txt")
ROS1_SEED = Path("/work/shared/seeds/000_d224704cab115b9f.txt")
ROS1_SOURCES = CORPUS / "ros1" / "ros_workshop" / "src"

# The ROS 1 seed's blocks, each by its first and last line in the seed, and the file it is in.
ROS1_BLOCKS = [
    ("perception.py", "import rospy ", "from geometry_msgs.msg import PoseArray "),
    ("perception.py", "boxes_message = PoseArray()", '    rospy.loginfo("Message received")'),
    ("perception.py", 'rospy.Subscriber("/simulator/boxes", PoseArray, callback)', None),
    ("perception.py", "# At the top of the file", "from geometry_msgs.msg import PoseArray, Polygon"),
    ("perception.py", "# Before the main loop", 'publisher = rospy.Publisher("perception/boxes", Polygon, queue_size=1)'),
    ("perception.py", "# Message is empty but can add points to it using polygon_message.points, which is an list of points", "polygon_message = Polygon() "),
    ("perception.py", "publisher.publish(polygon_message);", None),
    ("perception.py", "polygon_message.points.append(point);", None),
    ("ai.py", "from std_srvs.srv import Trigger, TriggerResponse", None),
    ("ai.py", "def sendTakeOffCommand():", '        rospy.logerr("Service class failed: %s", exception)'),
    ("control.py", "from std_srvs.srv import Trigger, TriggerResponse, TriggerRequest", None),
    ("control.py", "def handleTakeOffRequest(request):", "    return response"),
    ("control.py", "# Before main loop", 'take_off_service = rospy.Service("/control/take_off", Trigger, handleTakeOffRequest)'),
]  # fmt: skip


@pytest.mark.skipif(not SEED.is_file(), reason="the seed is not on this machine")
@pytest.mark.parametrize("name", ["send_message_skeleton.py", "receive_message_skeleton.py", "hello.py"])
def test_seed_block_is_verbatim(name: str) -> None:
    assert (CORPUS / "ros2" / name).read_text().rstrip("\n") in SEED.read_text()


def _seed_block(first: str, last: str | None) -> list[str]:
    lines = ROS1_SEED.read_text().split("\n")
    start = lines.index(first)
    return lines[start : (start if last is None else lines.index(last, start)) + 1]


def _pasted(block: list[str], lines: list[str]) -> bool:
    """Whether ``block`` is in ``lines`` line for line, each (but empty ones) behind one same indent."""
    for at in range(len(lines) - len(block) + 1):
        indent = lines[at][: len(lines[at]) - len(lines[at].lstrip(" "))]
        if all(lines[at + i] == (indent + line if line else line) for i, line in enumerate(block)):
            return True
    return False


@pytest.mark.skipif(not ROS1_SEED.is_file(), reason="the seed is not on this machine")
@pytest.mark.parametrize(("name", "first", "last"), ROS1_BLOCKS, ids=[f"{b[0]}:{b[1][:30]}" for b in ROS1_BLOCKS])
def test_ros1_seed_block_is_verbatim(name: str, first: str, last: str | None) -> None:
    block = _seed_block(first, last)
    assert _pasted(block, (ROS1_SOURCES / name).read_text().split("\n")), "\n".join(block)

