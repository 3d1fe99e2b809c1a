""" Drive the Neato forward and stop when the wall ahead is as close as asked """
import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node
from sensor_msgs.msg import LaserScan


class WallStopNode(Node):
    """Drives forward until the laser sees the wall closer than the 'distance' parameter."""
    def __init__(self):
        super().__init__('wall_stop')
        self.declare_parameter('distance', 0.5)
        self.distance_ahead = None
        self.stopped = False
        self.create_subscription(LaserScan, 'scan', self.process_scan, 10)
        self.vel_pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.timer = self.create_timer(0.05, self.run_loop)

    def process_scan(self, msg):
        """Keeps the distance straight ahead (0.0 means no return)."""
        if msg.ranges[0] != 0.0:
            self.distance_ahead = msg.ranges[0]

    def run_loop(self):
        """Drives forward, slower near the target, and stops for good once there."""
        msg = Twist()
        target = self.get_parameter('distance').value
        if self.distance_ahead is not None and not self.stopped:
            if self.distance_ahead > target:
                msg.linear.x = min(0.2, 0.05 + 0.5 * (self.distance_ahead - target))
            else:
                self.stopped = True
                self.get_logger().info(f'stopped: the wall is {self.distance_ahead:.2f} m ahead')
        self.vel_pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    node = WallStopNode()
    rclpy.spin(node)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
