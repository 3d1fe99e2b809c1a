""" Broadcast a carrot circling the world frame, and a fixed post beside it, with tf2 """
import math

import rclpy
from geometry_msgs.msg import TransformStamped
from rclpy.node import Node
from tf2_ros import StaticTransformBroadcaster, TransformBroadcaster
from tf_transformations import quaternion_from_euler


def set_yaw(t, yaw):
    q = quaternion_from_euler(0.0, 0.0, yaw)
    t.transform.rotation.x = q[0]
    t.transform.rotation.y = q[1]
    t.transform.rotation.z = q[2]
    t.transform.rotation.w = q[3]


class CarrotBroadcaster(Node):
    """world -> carrot turns once every 2*pi/speed seconds on a circle of radius 1 m;
    world -> post stands still 2 m ahead."""
    def __init__(self):
        super().__init__('carrot_broadcaster')
        self.declare_parameter('speed', 1.0)
        self.broadcaster = TransformBroadcaster(self)
        self.static_broadcaster = StaticTransformBroadcaster(self)
        post = TransformStamped()
        post.header.stamp = self.get_clock().now().to_msg()
        post.header.frame_id = 'world'
        post.child_frame_id = 'post'
        post.transform.translation.x = 2.0
        set_yaw(post, 0.0)
        self.static_broadcaster.sendTransform(post)
        self.start = self.get_clock().now()
        self.timer = self.create_timer(0.05, self.broadcast)

    def broadcast(self):
        now = self.get_clock().now()
        angle = self.get_parameter('speed').value * (now - self.start).nanoseconds / 1e9
        t = TransformStamped()
        t.header.stamp = now.to_msg()
        t.header.frame_id = 'world'
        t.child_frame_id = 'carrot'
        t.transform.translation.x = math.cos(angle)
        t.transform.translation.y = math.sin(angle)
        set_yaw(t, angle + math.pi / 2)
        self.broadcaster.sendTransform(t)


def main(args=None):
    rclpy.init(args=args)
    node = CarrotBroadcaster()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
