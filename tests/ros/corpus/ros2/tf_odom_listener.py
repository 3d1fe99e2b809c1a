""" Drive an arc and follow the robot in the odom frame with tf2 """
import math

import rclpy
from geometry_msgs.msg import PointStamped, TransformStamped, Twist
from nav_msgs.msg import Odometry
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.time import Time
from tf2_geometry_msgs import do_transform_point
from tf2_ros import ExtrapolationException, LookupException, TransformException
from tf2_ros.buffer import Buffer
from tf2_ros.static_transform_broadcaster import StaticTransformBroadcaster
from tf2_ros.transform_listener import TransformListener
from tf_transformations import euler_from_quaternion, quaternion_from_euler


def stamp_text(stamp):
    return f'{stamp.sec}.{stamp.nanosec:09d}'


class TfOdomListener(Node):
    """Prints where base_link is in odom (and a camera mounted on it), from tf2."""
    def __init__(self):
        super().__init__('tf_odom_listener')
        self.tf_buffer = Buffer()
        self.tf_listener = TransformListener(self.tf_buffer, self)
        # a camera 0.2 m ahead of the robot's centre, 0.1 m up, looking left
        self.static_broadcaster = StaticTransformBroadcaster(self)
        camera = TransformStamped()
        camera.header.stamp = self.get_clock().now().to_msg()
        camera.header.frame_id = 'base_link'
        camera.child_frame_id = 'camera_link'
        camera.transform.translation.x = 0.2
        camera.transform.translation.z = 0.1
        q = quaternion_from_euler(0.0, 0.0, math.pi / 2)
        camera.transform.rotation.x = q[0]
        camera.transform.rotation.y = q[1]
        camera.transform.rotation.z = q[2]
        camera.transform.rotation.w = q[3]
        self.static_broadcaster.sendTransform(camera)
        self.vel_pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.create_subscription(Odometry, 'odom', self.process_odom, 10)
        self.timer = self.create_timer(0.2, self.run_loop)
        self.odom_lookups = 0
        self.tried_errors = False

    def process_odom(self, msg):
        """The transform at this odometry message's own stamp (waiting for it a little)."""
        if self.odom_lookups >= 20:
            return
        try:
            t = self.tf_buffer.lookup_transform(
                'odom', 'base_link', Time.from_msg(msg.header.stamp), timeout=Duration(seconds=1.0))
        except TransformException as ex:
            self.get_logger().info(f'Could not transform base_link to odom: {ex}')
            return
        self.odom_lookups += 1
        self.print_pose('AT', t)

    def print_pose(self, label, t):
        q = t.transform.rotation
        yaw = euler_from_quaternion([q.x, q.y, q.z, q.w])[2]
        print(label, stamp_text(t.header.stamp), t.transform.translation.x, t.transform.translation.y, yaw, flush=True)

    def run_loop(self):
        msg = Twist()
        msg.linear.x = 0.2
        msg.angular.z = 0.5
        self.vel_pub.publish(msg)
        try:
            t = self.tf_buffer.lookup_transform('odom', 'base_link', Time())
        except TransformException as ex:
            self.get_logger().info(f'Could not transform base_link to odom: {ex}')
            return
        self.print_pose('LATEST', t)
        # a point 1 m in front of the camera, in the odom frame, at the same time
        seen = PointStamped()
        seen.header.frame_id = 'camera_link'
        seen.header.stamp = t.header.stamp
        seen.point.x = 1.0
        to_odom = self.tf_buffer.lookup_transform('odom', 'camera_link', Time.from_msg(t.header.stamp))
        p = do_transform_point(seen, to_odom).point
        also = self.tf_buffer.transform(seen, 'odom').point
        print('CAMERA', stamp_text(t.header.stamp), p.x, p.y, p.z, also.x, also.y, flush=True)
        if not self.tried_errors:
            self.tried_errors = True
            self.try_errors(Time.from_msg(t.header.stamp))

    def try_errors(self, latest):
        try:
            self.tf_buffer.lookup_transform('odom', 'base_link', latest + Duration(seconds=10.0))
        except ExtrapolationException as ex:
            print('FUTURE', ex, flush=True)
        try:
            self.tf_buffer.lookup_transform('odom', 'base_link', Time(nanoseconds=1))
        except ExtrapolationException as ex:
            print('PAST', ex, flush=True)
        try:
            self.tf_buffer.lookup_transform('odom', 'base_footprint', Time(), timeout=Duration(seconds=0.5))
        except LookupException as ex:
            print('LOOKUP', ex, flush=True)
        print('CAN', self.tf_buffer.can_transform('odom', 'camera_link', Time()), flush=True)


def main(args=None):
    rclpy.init(args=args)
    node = TfOdomListener()
    rclpy.spin(node)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
