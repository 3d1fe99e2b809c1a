"""A node that hangs: after a second of sim time its timer's callback never returns (a student's
loop waiting for something that never comes)."""

import time

import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node


class Hangs(Node):
    def __init__(self):
        super().__init__("hangs")
        self.publisher = self.create_publisher(Twist, "cmd_vel", 10)
        self.ticks = 0
        self.create_timer(0.1, self.tick)

    def tick(self):
        self.ticks += 1
        if self.ticks > 10:
            while True:  # never returns; sleeping, so as not to take a core from the tests
                time.sleep(0.05)
        command = Twist()
        command.linear.x = 0.1
        self.publisher.publish(command)


rclpy.init()
rclpy.spin(Hangs())
