""" Drive forward until the bumper touches something, then stop """
import rclpy
from geometry_msgs.msg import Twist
from neato2_interfaces.msg import Bump
from rclpy.node import Node


class BumpStopNode(Node):
    """A safety stop: any bumper switch pressed stops the robot for good."""
    def __init__(self):
        super().__init__('bump_stop')
        self.bumped = False
        self.create_subscription(Bump, 'bump', self.process_bump, 10)
        self.vel_pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.create_timer(0.1, self.run_loop)

    def process_bump(self, msg):
        if (msg.left_front or msg.right_front or msg.left_side or msg.right_side) and not self.bumped:
            self.bumped = True
            self.get_logger().info('bumped: stopping')

    def run_loop(self):
        msg = Twist()
        if not self.bumped:
            msg.linear.x = 0.15
        self.vel_pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    node = BumpStopNode()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
