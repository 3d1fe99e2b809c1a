# Two goals at once from one client, each with its own feedback, spun until both results are in.
import rclpy
from rclpy.action import ActionClient

from example_interfaces.action import Fibonacci


def main():
    rclpy.init()
    node = rclpy.create_node('fibonacci_two_goals')
    client = ActionClient(node, Fibonacci, 'fibonacci')
    client.wait_for_server()

    orders = (5, 7)
    feedback = {order: [] for order in orders}
    goal_futures = {
        order: client.send_goal_async(
            Fibonacci.Goal(order=order),
            feedback_callback=lambda msg, order=order: feedback[order].append(list(msg.feedback.sequence)))
        for order in orders
    }
    for future in goal_futures.values():
        rclpy.spin_until_future_complete(node, future)
    handles = {order: future.result() for order, future in goal_futures.items()}
    for order, handle in handles.items():
        node.get_logger().info(f'goal {order} accepted: {handle.accepted}')

    result_futures = {order: handle.get_result_async() for order, handle in handles.items()}
    for future in result_futures.values():
        rclpy.spin_until_future_complete(node, future)
    for order, future in result_futures.items():
        response = future.result()
        node.get_logger().info(
            f'goal {order} result: {list(response.result.sequence)} status {response.status} '
            f'feedback {len(feedback[order])}: {feedback[order][-1]}')
    rclpy.shutdown()


if __name__ == '__main__':
    main()
