"""This script explores publishing messages in Skydeck using Python (the seed's send_message.py).

Run it with `skydeck run examples/send_message.py` while the core runs.
"""

from services.runtime import Node, spin
from shared_models.geometry_msgs import Point, PointStamped
from shared_models.std_msgs import Header


class SendMessageNode(Node):
    """This is a message publishing node, which inherits from the Skydeck Node class."""

    def __init__(self):
        """Initializes the SendMessageNode. No inputs."""
        super().__init__("send_message_node")
        # Create a timer that fires ten times per second
        timer_period = 0.1
        self.timer = self.create_timer(timer_period, self.run_loop)
        self.publisher = self.create_publisher(PointStamped, "my_point", 10)

    def run_loop(self):
        """Publishes a PointStamped at (1, 2, 0) in the odom frame."""
        my_header = Header(stamp=self.get_clock().now().to_msg(), frame_id="odom")
        my_point = Point(x=1.0, y=2.0, z=0.0)
        my_point_stamped = PointStamped(header=my_header, point=my_point)
        self.publisher.publish(my_point_stamped)


def main(args=None):
    """Initializes a node, runs it, and cleans up after termination."""
    node = SendMessageNode()  # Create our Node
    spin(node)  # Run the Node until ready to shutdown


if __name__ == "__main__":
    main()
