"""A ROS 2 workspace with a package of launch files in the three formats, as a course writes them.

    ws/src/launch_demo/            ament_python: a parameterised talker, a listener
      launch/pair.launch.py        Node, DeclareLaunchArgument, LaunchConfiguration, PathJoinSubstitution,
                                   FindPackageShare, GroupAction + PushRosNamespace, IncludeLaunchDescription
      launch/pair.launch.xml       the same in ROS 2 XML
      launch/pair.launch.yaml      the same in ROS 2 YAML
      launch/listener.launch.py    included by each
      config/talker.yaml           a params file
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write_launch_workspace"]

_PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>launch_demo</name>
  <version>0.0.0</version>
  <description>Launching a talker and a listener</description>
  <maintainer email="student@example.com">student</maintainer>
  <license>Apache-2.0</license>
  <exec_depend>rclpy</exec_depend>
  <exec_depend>std_msgs</exec_depend>
  <export>
    <build_type>ament_python</build_type>
  </export>
</package>
"""

_SETUP_PY = """import os
from glob import glob

from setuptools import find_packages, setup

package_name = 'launch_demo'

setup(
    name=package_name,
    version='0.0.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'launch'), glob('launch/*')),
        (os.path.join('share', package_name, 'config'), glob('config/*.yaml')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    entry_points={
        'console_scripts': [
            'talker = launch_demo.talker:main',
            'listener = launch_demo.listener:main',
        ],
    },
)
"""

_TALKER = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):

    def __init__(self):
        super().__init__('talker')
        self.declare_parameter('greeting', 'hello')
        self.declare_parameter('rate', 10.0)
        self.declare_parameter('robot_id', 0)
        self.publisher = self.create_publisher(String, 'chatter', 10)
        self.timer = self.create_timer(1.0 / self.get_parameter('rate').value, self.tick)
        self.count = 0

    def tick(self):
        self.count += 1
        greeting = self.get_parameter('greeting').value
        self.publisher.publish(String(data=f'{greeting} {self.count}'))
        self.get_logger().info(f'said {greeting} {self.count}')


def main():
    rclpy.init()
    rclpy.spin(Talker())


if __name__ == '__main__':
    main()
"""

_LISTENER = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Listener(Node):

    def __init__(self):
        super().__init__('listener')
        self.create_subscription(String, 'chatter', self.heard, 10)

    def heard(self, msg):
        self.get_logger().info(f'heard {msg.data}')


def main():
    rclpy.init()
    rclpy.spin(Listener())


if __name__ == '__main__':
    main()
"""

_PARAMS = """/**:
  ros__parameters:
    rate: 20.0
    robot_id: 7
"""

_PAIR_PY = """import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node, PushRosNamespace
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    greeting = LaunchConfiguration('greeting')
    params = PathJoinSubstitution([FindPackageShare('launch_demo'), 'config', 'talker.yaml'])
    listener = os.path.join(get_package_share_directory('launch_demo'), 'launch', 'listener.launch.py')
    return LaunchDescription([
        DeclareLaunchArgument('greeting', default_value='hello', description='what the talker says'),
        DeclareLaunchArgument('robot', default_value='robot1'),
        GroupAction([
            PushRosNamespace(LaunchConfiguration('robot')),
            Node(
                package='launch_demo',
                executable='talker',
                name='speaker',
                parameters=[params, {'greeting': greeting}],
                remappings=[('chatter', 'news')],
                output='screen',
            ),
            IncludeLaunchDescription(
                PythonLaunchDescriptionSource(listener),
                launch_arguments={'topic': 'news'}.items(),
            ),
        ]),
    ])
"""

_LISTENER_PY = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('topic', default_value='chatter'),
        Node(
            package='launch_demo',
            executable='listener',
            name='ear',
            remappings=[('chatter', LaunchConfiguration('topic'))],
        ),
    ])
"""

_PAIR_XML = """<launch>
  <arg name="greeting" default="hello" description="what the talker says"/>
  <arg name="robot" default="robot1"/>
  <group>
    <push_ros_namespace namespace="$(var robot)"/>
    <node pkg="launch_demo" exec="talker" name="speaker" output="screen">
      <param from="$(find-pkg-share launch_demo)/config/talker.yaml"/>
      <param name="greeting" value="$(var greeting)"/>
      <remap from="chatter" to="news"/>
    </node>
    <include file="$(find-pkg-share launch_demo)/launch/listener.launch.py">
      <arg name="topic" value="news"/>
    </include>
  </group>
</launch>
"""

_PAIR_YAML = """launch:
- arg:
    name: greeting
    default: hello
    description: what the talker says
- arg:
    name: robot
    default: robot1
- group:
  - push_ros_namespace:
      namespace: $(var robot)
  - node:
      pkg: launch_demo
      exec: talker
      name: speaker
      output: screen
      param:
      - from: $(find-pkg-share launch_demo)/config/talker.yaml
      - name: greeting
        value: $(var greeting)
      remap:
      - from: chatter
        to: news
  - include:
      file: $(find-pkg-share launch_demo)/launch/listener.launch.py
      arg:
      - name: topic
        value: news
"""


def write_launch_workspace(root: Path) -> Path:
    """Write the workspace under ``root`` (``root/src/launch_demo``); returns ``root``."""
    files = {
        "package.xml": _PACKAGE_XML,
        "setup.py": _SETUP_PY,
        "setup.cfg": "[develop]\nscript_dir=$base/lib/launch_demo\n[install]\ninstall_scripts=$base/lib/launch_demo\n",
        "resource/launch_demo": "",
        "launch_demo/__init__.py": "",
        "launch_demo/talker.py": _TALKER,
        "launch_demo/listener.py": _LISTENER,
        "config/talker.yaml": _PARAMS,
        "launch/pair.launch.py": _PAIR_PY,
        "launch/listener.launch.py": _LISTENER_PY,
        "launch/pair.launch.xml": _PAIR_XML,
        "launch/pair.launch.yaml": _PAIR_YAML,
    }
    for relative, text in files.items():
        path = root / "src" / "launch_demo" / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root
