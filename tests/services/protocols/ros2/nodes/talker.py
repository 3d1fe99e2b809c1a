"""An unmodified rclpy talker (ROS 2's demo, as a student writes it)."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Talker(Node):
    def __init__(self):
        super().__init__("talker")
        self.publisher = self.create_publisher(String, "chatter", 10)
        self.count = 0
        self.create_timer(0.1, self.tick)

    def tick(self):
        self.count += 1
        self.publisher.publish(String(data=f"hello {self.count}"))


def main():
    rclpy.init()
    rclpy.spin(Talker())


if __name__ == "__main__":
    main()
