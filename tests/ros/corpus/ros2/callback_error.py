""" A subscription callback with a bug: the node must keep running and say where the bug is """
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import LaserScan


class BuggyNode(Node):
    def __init__(self):
        super().__init__('buggy')
        self.scans = 0
        self.create_subscription(LaserScan, 'scan', self.process_scan, 10)
        self.create_timer(0.5, self.report)

    def process_scan(self, msg):
        self.scans += 1
        if self.scans == 1:
            print(msg.ranges[400])  # only 360 beams: IndexError, once

    def report(self):
        print(f'still running, {self.scans} scans so far')


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(BuggyNode())


if __name__ == '__main__':
    main()
