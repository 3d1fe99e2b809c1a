"""An unmodified rclpy node on the robot world through the bridge: reads /scan (sensor QoS),
/odom and /tf_static, drives with /cmd_vel, and runs on sim time (use_sim_time).

Prints one line per finding: `scan RANGES ZEROS FRAME`, `tf_static PARENT>CHILD...`,
`clock SECONDS`, `moved METRES`.
"""

import time

import rclpy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, QoSProfile, qos_profile_sensor_data
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage


def main():
    rclpy.init()
    node = Node("robot_driver", parameter_overrides=[Parameter("use_sim_time", value=True)])
    seen = {}
    odom = []
    node.create_subscription(LaserScan, "/scan", lambda m: seen.setdefault("scan", m), qos_profile_sensor_data)
    node.create_subscription(Odometry, "/odom", lambda m: odom.append(m.pose.pose.position.x), 10)
    latched = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(TFMessage, "/tf_static", lambda m: seen.setdefault("tf_static", m), latched)
    cmd_vel = node.create_publisher(Twist, "/cmd_vel", 10)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not ({"scan", "tf_static"} <= set(seen) and len(odom) > 3):
        rclpy.spin_once(node, timeout_sec=0.1)
    scan = seen["scan"]
    print("scan", len(scan.ranges), sum(1 for r in scan.ranges if r == 0.0), scan.header.frame_id, flush=True)
    pairs = [f"{t.header.frame_id}>{t.child_frame_id}" for t in seen["tf_static"].transforms]
    print("tf_static", *pairs, flush=True)
    print("clock", node.get_clock().now().nanoseconds / 1e9, flush=True)
    start = odom[-1]
    forward = Twist()
    forward.linear.x = 0.3
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and odom[-1] - start < 0.3:
        cmd_vel.publish(forward)
        rclpy.spin_once(node, timeout_sec=0.05)
    cmd_vel.publish(Twist())
    print("moved", odom[-1] - start, flush=True)


if __name__ == "__main__":
    main()
