"""A ROS 2 workspace as a course has students write one, made in a temporary folder.

    ros2_ws/src/tutorial_interfaces/   ament_cmake: msg/Num.msg, msg/Sphere.msg, srv/AddThreeInts.srv
    ros2_ws/src/py_pubsub/             ament_python: a talker, a listener, a service and a client,
                                       with a helper module imported relatively
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write_workspace"]

_INTERFACES_XML = """<?xml version="1.0"?>
<?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
<package format="3">
  <name>tutorial_interfaces</name>
  <version>0.0.0</version>
  <description>Our own messages and services</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>Apache-2.0</license>

  <buildtool_depend>ament_cmake</buildtool_depend>
  <depend>geometry_msgs</depend>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
  <exec_depend>rosidl_default_runtime</exec_depend>
  <member_of_group>rosidl_interface_packages</member_of_group>

  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
"""

_CMAKE = """cmake_minimum_required(VERSION 3.8)
project(tutorial_interfaces)

find_package(ament_cmake REQUIRED)
find_package(geometry_msgs REQUIRED)
find_package(rosidl_default_generators REQUIRED)

rosidl_generate_interfaces(${PROJECT_NAME}
  "msg/Num.msg"
  "msg/Sphere.msg"
  "srv/AddThreeInts.srv"
  DEPENDENCIES geometry_msgs
)

ament_package()
"""

_PUBSUB_XML = """<?xml version="1.0"?>
<package format="3">
  <name>py_pubsub</name>
  <version>0.0.0</version>
  <description>Talking with our own messages</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>Apache-2.0</license>

  <exec_depend>rclpy</exec_depend>
  <exec_depend>tutorial_interfaces</exec_depend>

  <export>
    <build_type>ament_python</build_type>
  </export>
</package>
"""

_SETUP_PY = """from setuptools import find_packages, setup

package_name = 'py_pubsub'

setup(
    name=package_name,
    version='0.0.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages',
            ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='student',
    maintainer_email='student@example.com',
    description='Talking with our own messages',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'talker = py_pubsub.publisher_member_function:main',
            'listener = py_pubsub.subscriber_member_function:main',
            f'service = {package_name}.service_member_function:main',
            'client = ' + package_name + '.client_member_function:main',
        ],
    },
)
"""

_SETUP_CFG = """[develop]
script_dir=$base/lib/py_pubsub
[install]
install_scripts=$base/lib/py_pubsub
"""

_COUNTING = """def next_count(count):
    \"\"\"The number after count, as the talker counts.\"\"\"
    return count + 1
"""

_TALKER = """import rclpy
from rclpy.node import Node

from geometry_msgs.msg import Point
from tutorial_interfaces.msg import Num, Sphere

from .counting import next_count


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(Num, 'topic', 10)
        self.sphere_publisher = self.create_publisher(Sphere, 'sphere', 10)
        timer_period = 0.1  # seconds
        self.timer = self.create_timer(timer_period, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = Num()
        self.i = next_count(self.i)
        msg.num = self.i
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%d"' % msg.num)
        self.sphere_publisher.publish(Sphere(center=Point(x=1.0, y=2.0, z=3.0), radius=0.5))


def main(args=None):
    rclpy.init(args=args)

    minimal_publisher = MinimalPublisher()

    rclpy.spin(minimal_publisher)

    minimal_publisher.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
"""

_LISTENER = """import rclpy
from rclpy.node import Node

from tutorial_interfaces.msg import Num


class MinimalSubscriber(Node):

    def __init__(self):
        super().__init__('minimal_subscriber')
        self.subscription = self.create_subscription(Num, 'topic', self.listener_callback, 10)

    def listener_callback(self, msg):
        self.get_logger().info('I heard: "%d"' % msg.num)


def main(args=None):
    rclpy.init(args=args)
    minimal_subscriber = MinimalSubscriber()
    rclpy.spin(minimal_subscriber)
    minimal_subscriber.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
"""

_SERVICE = """import rclpy
from rclpy.node import Node

from tutorial_interfaces.srv import AddThreeInts


class MinimalService(Node):

    def __init__(self):
        super().__init__('minimal_service')
        self.srv = self.create_service(AddThreeInts, 'add_three_ints', self.add_three_ints_callback)

    def add_three_ints_callback(self, request, response):
        response.sum = request.a + request.b + request.c
        self.get_logger().info('Incoming request\\na: %d b: %d c: %d' % (request.a, request.b, request.c))
        return response


def main():
    rclpy.init()
    minimal_service = MinimalService()
    rclpy.spin(minimal_service)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
"""

_CLIENT = """import sys

import rclpy
from rclpy.node import Node

from tutorial_interfaces.srv import AddThreeInts


class MinimalClientAsync(Node):

    def __init__(self):
        super().__init__('minimal_client_async')
        self.cli = self.create_client(AddThreeInts, 'add_three_ints')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again...')
        self.req = AddThreeInts.Request()

    def send_request(self, a, b, c):
        self.req.a = a
        self.req.b = b
        self.req.c = c
        return self.cli.call_async(self.req)


def main():
    rclpy.init()
    minimal_client = MinimalClientAsync()
    future = minimal_client.send_request(int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))
    rclpy.spin_until_future_complete(minimal_client, future)
    response = future.result()
    minimal_client.get_logger().info(
        'Result of add_three_ints: for %d + %d + %d = %d' %
        (int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), response.sum))
    minimal_client.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
"""


def write_workspace(root: Path) -> Path:
    """Write the workspace under ``root`` (``root/src/...``); returns ``root``."""
    files = {
        "src/tutorial_interfaces/package.xml": _INTERFACES_XML,
        "src/tutorial_interfaces/CMakeLists.txt": _CMAKE,
        "src/tutorial_interfaces/msg/Num.msg": "int64 num\n",
        "src/tutorial_interfaces/msg/Sphere.msg": "geometry_msgs/Point center\nfloat64 radius\n",
        "src/tutorial_interfaces/srv/AddThreeInts.srv": "int64 a\nint64 b\nint64 c\n---\nint64 sum\n",
        "src/py_pubsub/package.xml": _PUBSUB_XML,
        "src/py_pubsub/setup.py": _SETUP_PY,
        "src/py_pubsub/setup.cfg": _SETUP_CFG,
        "src/py_pubsub/resource/py_pubsub": "",
        "src/py_pubsub/py_pubsub/__init__.py": "",
        "src/py_pubsub/py_pubsub/counting.py": _COUNTING,
        "src/py_pubsub/py_pubsub/publisher_member_function.py": _TALKER,
        "src/py_pubsub/py_pubsub/subscriber_member_function.py": _LISTENER,
        "src/py_pubsub/py_pubsub/service_member_function.py": _SERVICE,
        "src/py_pubsub/py_pubsub/client_member_function.py": _CLIENT,
    }
    for relative, text in files.items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root
