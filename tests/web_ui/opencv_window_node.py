"""A ROS 2 node with an OpenCV window, written as a course writes one: a thread draws a grey
canvas whose level a trackbar sets, marks where the mouse clicked, and paces itself with
``cv2.waitKey(5)``; what its callbacks and waitKey saw is printed, with the thread they ran in.
Run by ``skydeck run`` in tests/web_ui/test_opencv_windows.py."""

import threading

import cv2
import numpy as np
import rclpy
from rclpy.node import Node


class WindowNode(Node):
    def __init__(self):
        super().__init__('window_node')
        self.level = 40
        self.click = None
        threading.Thread(target=self.loop, name='drawing', daemon=True).start()

    def set_level(self, value):
        self.level = value
        print(f'TRACKBAR {value} {threading.current_thread().name}', flush=True)

    def on_mouse(self, event, x, y, flags, param):
        if event == cv2.EVENT_LBUTTONDOWN:
            self.click = (x, y)
            print(f'CLICK {x} {y} {flags} {param} {threading.current_thread().name}', flush=True)

    def loop(self):
        cv2.namedWindow('canvas')
        cv2.createTrackbar('level', 'canvas', self.level, 255, self.set_level)
        cv2.setMouseCallback('canvas', self.on_mouse, 'clicked')
        while rclpy.ok():
            image = np.full((120, 160, 3), self.level, np.uint8)
            if self.click is not None:
                cv2.circle(image, self.click, 8, (0, 0, 255), -1)
            cv2.imshow('canvas', image)
            key = cv2.waitKey(5)
            if key != -1:
                print(f'KEY {key} {threading.current_thread().name}', flush=True)


def main():
    rclpy.init()
    rclpy.spin(WindowNode())


if __name__ == '__main__':
    main()
