"""An unmodified rclpy node publishing a type Skydeck does not have, and one it has."""

import rclpy
from lifecycle_msgs.msg import TransitionEvent
from rclpy.node import Node
from std_msgs.msg import String


def main():
    rclpy.init()
    node = Node("odd")
    odd = node.create_publisher(TransitionEvent, "/odd", 10)
    fine = node.create_publisher(String, "/fine", 10)

    def tick():
        odd.publish(TransitionEvent())
        fine.publish(String(data="fine"))

    node.create_timer(0.1, tick)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
