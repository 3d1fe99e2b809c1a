# An action server as the course writes one: the Fibonacci sequence, one number a step, with
# feedback after each; goals of order 0 or less (or over 46: int32) are refused; cancels are
# accepted. A MultiThreadedExecutor runs several goals at once.
import time

import rclpy
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node

from example_interfaces.action import Fibonacci


class FibonacciActionServer(Node):

    def __init__(self):
        super().__init__('fibonacci_action_server')
        self.declare_parameter('step', 1.0)
        self._action_server = ActionServer(
            self,
            Fibonacci,
            'fibonacci',
            execute_callback=self.execute_callback,
            callback_group=ReentrantCallbackGroup(),
            goal_callback=self.goal_callback,
            cancel_callback=self.cancel_callback)

    def goal_callback(self, goal_request):
        if goal_request.order <= 0 or goal_request.order > 46:
            self.get_logger().info(f'Rejecting goal request (order {goal_request.order})')
            return GoalResponse.REJECT
        self.get_logger().info(f'Accepting goal request (order {goal_request.order})')
        return GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle):
        self.get_logger().info('Received cancel request')
        return CancelResponse.ACCEPT

    def execute_callback(self, goal_handle):
        self.get_logger().info('Executing goal...')
        step = self.get_parameter('step').value
        feedback_msg = Fibonacci.Feedback()
        feedback_msg.sequence = [0, 1]

        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                self.get_logger().info('Goal canceled')
                return Fibonacci.Result(sequence=feedback_msg.sequence)

            feedback_msg.sequence.append(feedback_msg.sequence[i] + feedback_msg.sequence[i - 1])
            self.get_logger().info(f'Publishing feedback: {list(feedback_msg.sequence)}')
            goal_handle.publish_feedback(feedback_msg)
            time.sleep(step)

        goal_handle.succeed()

        result = Fibonacci.Result()
        result.sequence = feedback_msg.sequence
        self.get_logger().info(f'Returning result: {list(result.sequence)}')
        return result


def main(args=None):
    rclpy.init(args=args)
    fibonacci_action_server = FibonacciActionServer()
    executor = MultiThreadedExecutor()
    rclpy.spin(fibonacci_action_server, executor=executor)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
