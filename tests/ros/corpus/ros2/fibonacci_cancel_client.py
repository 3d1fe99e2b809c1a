# Cancelling a goal mid-way, as the course's cancel example does: two seconds after the goal is
# accepted, a timer asks to cancel it; the result then comes with status CANCELED.
import rclpy
from action_msgs.msg import GoalStatus
from rclpy.action import ActionClient
from rclpy.node import Node

from example_interfaces.action import Fibonacci


class MinimalActionClient(Node):

    def __init__(self):
        super().__init__('fibonacci_cancel_client')
        self._action_client = ActionClient(self, Fibonacci, 'fibonacci')

    def cancel_done(self, future):
        cancel_response = future.result()
        if len(cancel_response.goals_canceling) > 0:
            self.get_logger().info('Goal successfully canceled')
        else:
            self.get_logger().info('Goal failed to cancel')

    def feedback_callback(self, feedback):
        self.get_logger().info(f'Received feedback: {list(feedback.feedback.sequence)}')

    def goal_response_callback(self, future):
        goal_handle = future.result()
        if not goal_handle.accepted:
            self.get_logger().info('Goal rejected :(')
            return
        self._goal_handle = goal_handle
        self.get_logger().info('Goal accepted :)')
        self._get_result_future = goal_handle.get_result_async()
        self._get_result_future.add_done_callback(self.get_result_callback)
        # Start a 2 second timer
        self._timer = self.create_timer(2.0, self.timer_callback)

    def timer_callback(self):
        self.get_logger().info('Canceling goal')
        future = self._goal_handle.cancel_goal_async()
        future.add_done_callback(self.cancel_done)
        self._timer.cancel()

    def get_result_callback(self, future):
        status = future.result().status
        if status == GoalStatus.STATUS_CANCELED:
            self.get_logger().info(f'Goal canceled with result: {list(future.result().result.sequence)}')
        else:
            self.get_logger().info(f'Goal ended with status {status}')
        rclpy.shutdown()

    def send_goal(self):
        self.get_logger().info('Waiting for action server...')
        self._action_client.wait_for_server()
        goal_msg = Fibonacci.Goal(order=40)
        self.get_logger().info('Sending goal request...')
        self._send_goal_future = self._action_client.send_goal_async(
            goal_msg, feedback_callback=self.feedback_callback)
        self._send_goal_future.add_done_callback(self.goal_response_callback)


def main(args=None):
    rclpy.init(args=args)
    action_client = MinimalActionClient()
    action_client.send_goal()
    rclpy.spin(action_client)


if __name__ == '__main__':
    main()
