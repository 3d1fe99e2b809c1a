""" A ball tracker for the Neato, written the way the computer-vision day of the course writes one:
    the camera's images through cv_bridge, a colour threshold in HSV tuned with trackbars, the
    image and the mask shown in OpenCV windows, and cmd_vel steering towards the ball.

    skydeck launch soccer                       # the room with a ball (another terminal)
    skydeck run examples/robot/ball_tracker.py

    The windows appear in the dashboard's Windows tab: drag the sliders until only the ball is
    white in binary_window, click the ball in video_window to see its HSV values in image_info.
    Press 'q' in a window to stop the robot and quit. """

from threading import Thread

import cv2
import numpy as np
import rclpy
from cv_bridge import CvBridge
from geometry_msgs.msg import Twist
from rclpy.node import Node
from sensor_msgs.msg import Image


class BallTracker(Node):
    """ Finds the ball in the camera's images and drives towards it, keeping it in the middle
        of the picture. """

    def __init__(self, image_topic):
        super().__init__('ball_tracker')
        self.cv_image = None            # the newest camera image, in OpenCV's BGR
        self.bridge = CvBridge()
        self.hsv_lower = [0, 150, 80]     # hue, saturation, value: the ball's colour from here...
        self.hsv_upper = [12, 255, 255]   # ...to here (OpenCV's hue goes from 0 to 179)
        self.min_area = 30              # fewer white pixels than this: no ball in sight
        self.forward_speed = 0.15
        self.turn_gain = 0.8
        self.search_turn = 0.35
        self.running = True
        self.ball_seen = False
        self.create_subscription(Image, image_topic, self.process_image, 10)
        self.pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.loop_thread = Thread(target=self.loop_wrapper)
        self.loop_thread.start()

    def process_image(self, msg):
        """ Keep the newest image; the loop works on it at its own pace. """
        self.cv_image = self.bridge.imgmsg_to_cv2(msg, desired_encoding='bgr8')

    def loop_wrapper(self):
        """ OpenCV's windows belong to one thread: make them here, then run the loop. """
        cv2.namedWindow('video_window')
        cv2.namedWindow('binary_window')
        cv2.namedWindow('image_info')
        names = ['hue', 'saturation', 'value']
        maxima = [179, 255, 255]
        for i in range(3):
            cv2.createTrackbar(f'{names[i]} lower', 'binary_window', self.hsv_lower[i], maxima[i],
                               lambda value, i=i: self.set_bound(self.hsv_lower, i, value))
            cv2.createTrackbar(f'{names[i]} upper', 'binary_window', self.hsv_upper[i], maxima[i],
                               lambda value, i=i: self.set_bound(self.hsv_upper, i, value))
        cv2.setMouseCallback('video_window', self.process_mouse_event)
        while self.running and rclpy.ok():
            self.run_loop()
        self.pub.publish(Twist())       # stopped
        rclpy.try_shutdown()            # and rclpy.spin in main returns

    def set_bound(self, bounds, index, value):
        bounds[index] = value

    def process_mouse_event(self, event, x, y, flags, param):
        """ A click on the video shows the colour under the mouse, in BGR and HSV. """
        if event != cv2.EVENT_LBUTTONDOWN or self.cv_image is None:
            return
        blue, green, red = self.cv_image[y, x]
        hue, saturation, value = cv2.cvtColor(self.cv_image[y:y + 1, x:x + 1], cv2.COLOR_BGR2HSV)[0, 0]
        info = np.zeros((90, 360, 3), np.uint8)
        info[:] = (int(blue), int(green), int(red))
        text_colour = (255, 255, 255) if value < 128 else (0, 0, 0)
        cv2.putText(info, f'({x}, {y}) BGR {blue} {green} {red}', (8, 35), cv2.FONT_HERSHEY_SIMPLEX, 0.55, text_colour)
        cv2.putText(info, f'HSV {hue} {saturation} {value}', (8, 65), cv2.FONT_HERSHEY_SIMPLEX, 0.55, text_colour)
        cv2.imshow('image_info', info)
        self.get_logger().info(f'clicked ({x}, {y}): HSV {hue} {saturation} {value}')

    def run_loop(self):
        if self.cv_image is None:
            if cv2.waitKey(50) == ord('q'):
                self.running = False
            return
        image = self.cv_image
        hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
        binary = cv2.inRange(hsv, np.array(self.hsv_lower), np.array(self.hsv_upper))
        moments = cv2.moments(binary, binaryImage=True)
        twist = Twist()
        if moments['m00'] >= self.min_area:
            x = moments['m10'] / moments['m00']
            y = moments['m01'] / moments['m00']
            if not self.ball_seen:
                self.ball_seen = True
                self.get_logger().info(f'ball in sight at ({x:.0f}, {y:.0f}) in the image: following it')
            offset = (x - image.shape[1] / 2) / (image.shape[1] / 2)   # -1 at the left edge, 1 at the right
            twist.linear.x = self.forward_speed * (1.0 - min(abs(offset), 1.0))
            twist.angular.z = -self.turn_gain * offset
            shown = image.copy()
            cv2.circle(shown, (int(x), int(y)), 6, (0, 255, 0), 2)
        else:
            twist.angular.z = self.search_turn   # look around for it
            shown = image
        self.pub.publish(twist)
        cv2.imshow('video_window', shown)
        cv2.imshow('binary_window', binary)
        if cv2.waitKey(100) == ord('q'):
            self.running = False


def main(args=None):
    rclpy.init(args=args)
    node = BallTracker('camera/image_raw')
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:   # Ctrl-C: stop the robot on the way out
        node.pub.publish(Twist())
    # End the loop's thread before the program ends: Python stops a thread that is still
    # running when it exits wherever it is, even inside OpenCV, which aborts the program.
    node.running = False
    node.loop_thread.join()
    node.destroy_node()
    rclpy.try_shutdown()


if __name__ == '__main__':
    main()
