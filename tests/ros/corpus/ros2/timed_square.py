""" Drive a 1 m square by the clock: each side and each turn lasts as long as it should """
import math
import threading

import rclpy
from geometry_msgs.msg import Twist
from rclpy.duration import Duration

SIDE = 1.0          # m
SPEED = 0.2         # m/s
TURN_RATE = 0.5     # rad/s


def drive_for(node, publisher, rate, seconds, linear, angular):
    """Sends one command at the rate until the node's clock says the time is up."""
    start = node.get_clock().now()
    while rclpy.ok() and node.get_clock().now() - start < Duration(seconds=seconds):
        msg = Twist()
        msg.linear.x = linear
        msg.angular.z = angular
        publisher.publish(msg)
        rate.sleep()


def main(args=None):
    rclpy.init(args=args)
    node = rclpy.create_node('timed_square')
    publisher = node.create_publisher(Twist, 'cmd_vel', 10)
    spinner = threading.Thread(target=rclpy.spin, args=(node,), daemon=True)
    spinner.start()
    rate = node.create_rate(20)
    for side in range(4):
        drive_for(node, publisher, rate, SIDE / SPEED, SPEED, 0.0)
        drive_for(node, publisher, rate, (math.pi / 2) / TURN_RATE, 0.0, TURN_RATE)
        node.get_logger().info(f'side {side + 1} done')
    publisher.publish(Twist())
    node.get_logger().info('square done')
    rclpy.shutdown()


if __name__ == '__main__':
    main()
