""" Look through the simulator's camera with cv_bridge and OpenCV """
import cv2
import rclpy
from cv_bridge import CvBridge
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage, Image


def stamp_text(stamp):
    return f'{stamp.sec}.{stamp.nanosec:09d}'


class CameraBridge(Node):
    """Prints the average colour of each camera frame and republishes it in grey and as edges."""
    def __init__(self):
        super().__init__('camera_bridge')
        self.bridge = CvBridge()
        self.create_subscription(Image, '/simulator/camera/image_raw', self.process_image, 10)
        self.create_subscription(CompressedImage, '/simulator/camera', self.process_compressed, 10)
        self.gray_pub = self.create_publisher(Image, 'camera/gray', 10)
        self.edges_pub = self.create_publisher(CompressedImage, 'camera/edges/compressed', 10)

    def process_image(self, msg):
        frame = self.bridge.imgmsg_to_cv2(msg, desired_encoding='bgr8')
        blue, green, red = (frame[:, :, i].mean() for i in range(3))
        print('RAW', stamp_text(msg.header.stamp), frame.shape[1], frame.shape[0], blue, green, red, flush=True)
        gray = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
        self.gray_pub.publish(self.bridge.cv2_to_imgmsg(gray, encoding='mono8', header=msg.header))
        edges = cv2.Canny(gray, 50, 150)
        self.edges_pub.publish(self.bridge.cv2_to_compressed_imgmsg(edges, dst_format='png'))

    def process_compressed(self, msg):
        frame = self.bridge.compressed_imgmsg_to_cv2(msg, desired_encoding='rgb8')
        red, green, blue = (frame[:, :, i].mean() for i in range(3))
        print('JPEG', stamp_text(msg.header.stamp), blue, green, red, flush=True)


def main(args=None):
    rclpy.init(args=args)
    node = CameraBridge()
    rclpy.spin(node)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
