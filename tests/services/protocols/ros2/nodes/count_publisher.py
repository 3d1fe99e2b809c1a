"""A ROS 2 program run by `skydeck run` (so on Skydeck's rclpy façade, even with the real
rclpy installed): publishes std_msgs/Int32 1, 2, 3... on /count at 20 Hz."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import Int32


def main():
    rclpy.init()
    node = Node("count_publisher")
    print("rclpy is", rclpy.__name__, rclpy.__file__, flush=True)
    publisher = node.create_publisher(Int32, "/count", 100)
    state = {"n": 0}

    def tick():
        state["n"] += 1
        publisher.publish(Int32(data=state["n"]))

    node.create_timer(0.05, tick)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
