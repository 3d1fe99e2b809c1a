"""Investigate receiving a message using a callback function (the seed's receive_message.py).

Run it with `skydeck run examples/receive_message.py` next to send_message.py.
"""

from services.runtime import Node, spin
from shared_models.geometry_msgs import PointStamped


class ReceiveMessageNode(Node):
    """This is a message subscription node, which inherits from the Skydeck Node class."""

    def __init__(self):
        """Initializes the ReceiveMessageNode. No inputs."""
        super().__init__("receive_message_node")
        self.sub = self.create_subscription(PointStamped, "my_point", self.process_point, 10)

    def process_point(self, msg):
        """Takes msg input and prints the header of that message."""
        print(msg.header, flush=True)


def main(args=None):
    """Initializes a node, runs it, and cleans up after termination."""
    node = ReceiveMessageNode()
    spin(node)


if __name__ == "__main__":
    main()
