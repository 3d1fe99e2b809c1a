"""A deliberately wrong wall follower (rclpy): it drives straight ahead, into the +x wall."""

import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node


class IntoTheWall(Node):
    def __init__(self):
        super().__init__("into_the_wall")
        self.publisher = self.create_publisher(Twist, "cmd_vel", 10)
        self.create_timer(0.1, self.run_loop)

    def run_loop(self):
        msg = Twist()
        msg.linear.x = 0.25
        self.publisher.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(IntoTheWall())


if __name__ == "__main__":
    main()
