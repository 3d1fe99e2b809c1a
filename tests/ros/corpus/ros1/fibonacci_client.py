#! /usr/bin/env python
# A SimpleActionClient as the ROS 1 course writes one: send a goal, wait for the result.
# `fibonacci_client.py ORDER` (20 by default); `_cancel_after:=N` cancels after N feedbacks.
import sys

import rospy

import actionlib

import actionlib_tutorials.msg

feedbacks = []


def feedback_cb(feedback):
    feedbacks.append(list(feedback.sequence))
    print('feedback: %s' % list(feedback.sequence), flush=True)


def active_cb():
    print('active', flush=True)


def done_cb(state, result):
    print('done: state %d' % state, flush=True)


def fibonacci_client(order):
    client = actionlib.SimpleActionClient('fibonacci', actionlib_tutorials.msg.FibonacciAction)
    client.wait_for_server()
    goal = actionlib_tutorials.msg.FibonacciGoal(order=order)
    client.send_goal(goal, done_cb=done_cb, active_cb=active_cb, feedback_cb=feedback_cb)
    cancel_after = rospy.get_param('~cancel_after', 0)
    if cancel_after:
        while len(feedbacks) < cancel_after and not rospy.is_shutdown():
            rospy.sleep(0.01)
        client.cancel_goal()
    client.wait_for_result()
    print('state: %s' % actionlib.get_name_of_constant(actionlib.GoalStatus, client.get_state()), flush=True)
    return client.get_result()


if __name__ == '__main__':
    try:
        rospy.init_node('fibonacci_client_py')
        order = int(rospy.myargv(argv=sys.argv)[1]) if len(rospy.myargv(argv=sys.argv)) > 1 else 20
        result = fibonacci_client(order)
        print("Result:", ', '.join([str(n) for n in result.sequence]), flush=True)
    except rospy.ROSInterruptException:
        print("program interrupted before completion", file=sys.stderr)
