"""A first behaviour for the Neato: drive forward, and stop when the wall ahead is near."""

from services.runtime import Node, spin
from shared_models.geometry_msgs import Twist
from shared_models.sensor_msgs import LaserScan


class MyEstop(Node):
    def __init__(self):
        super().__init__("my_estop")
        self.distance_ahead = None
        self.stopped = False
        self.create_subscription(LaserScan, "scan", self.process_scan, 10)
        self.publisher = self.create_publisher(Twist, "cmd_vel", 10)
        self.create_timer(0.1, self.run_loop)

    def process_scan(self, msg):
        if msg.ranges[0] != 0.0:  # 0.0: no return straight ahead
            self.distance_ahead = msg.ranges[0]

    def run_loop(self):
        msg = Twist()
        if self.distance_ahead is not None and self.distance_ahead > 0.6:
            msg.linear.x = 0.2
        elif self.distance_ahead is not None and not self.stopped:
            self.stopped = True
            self.get_logger().info("stopped: the wall is %.2f m ahead", self.distance_ahead)
        self.publisher.publish(msg)


if __name__ == "__main__":
    spin(MyEstop())
