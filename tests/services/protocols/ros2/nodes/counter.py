"""An unmodified rclpy subscriber that prints each std_msgs/Int32 it gets on /count."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import Int32


def main():
    rclpy.init()
    node = Node("counter")
    node.create_subscription(Int32, "/count", lambda m: print("got", m.data, flush=True), 100)
    print("listening", flush=True)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
