"""An unmodified rclpy client: calls the Trigger service named on the command line once."""

import sys

import rclpy
from rclpy.node import Node
from std_srvs.srv import Trigger


def main():
    rclpy.init()
    node = Node("caller")
    client = node.create_client(Trigger, sys.argv[1])
    if not client.wait_for_service(timeout_sec=20.0):
        print("no service", flush=True)
        return
    future = client.call_async(Trigger.Request())
    rclpy.spin_until_future_complete(node, future, timeout_sec=20.0)
    response = future.result()
    print("answer", response.success, response.message, flush=True)


if __name__ == "__main__":
    main()
