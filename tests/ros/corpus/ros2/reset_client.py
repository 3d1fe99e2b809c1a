""" Call the simulator's reset service once, asynchronously, and report the answer """
import sys

import rclpy
from rclpy.node import Node
from std_srvs.srv import Trigger


class ResetClient(Node):
    def __init__(self):
        super().__init__('reset_client')
        self.cli = self.create_client(Trigger, '/simulator/reset')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again...')
        self.req = Trigger.Request()

    def send_request(self):
        self.future = self.cli.call_async(self.req)
        rclpy.spin_until_future_complete(self, self.future)
        return self.future.result()


def main(args=None):
    rclpy.init(args=args)
    client = ResetClient()
    response = client.send_request()
    client.get_logger().info(f'reset answered: success={response.success} message={response.message!r}')
    client.destroy_node()
    rclpy.shutdown()
    return 0 if response.success else 1


if __name__ == '__main__':
    sys.exit(main())
