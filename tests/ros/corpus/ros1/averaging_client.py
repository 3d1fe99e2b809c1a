#! /usr/bin/env python
# The averaging action's client: send_goal_and_wait with a timeout, as a scripted client does.
# `averaging_client.py SAMPLES [EXECUTE_TIMEOUT_S]`.
import sys

import rospy

import actionlib

import actionlib_tutorials.msg

if __name__ == '__main__':
    rospy.init_node('averaging_client')
    argv = rospy.myargv(argv=sys.argv)
    samples = int(argv[1])
    timeout = rospy.Duration(float(argv[2])) if len(argv) > 2 else rospy.Duration()
    client = actionlib.SimpleActionClient('averaging', actionlib_tutorials.msg.AveragingAction)
    client.wait_for_server()
    state = client.send_goal_and_wait(actionlib_tutorials.msg.AveragingGoal(samples=samples),
                                      execute_timeout=timeout, preempt_timeout=rospy.Duration(5))
    result = client.get_result()
    print('state: %s' % actionlib.get_name_of_constant(actionlib.GoalStatus, state), flush=True)
    print('mean: %.2f std_dev: %.3f text: %s' % (result.mean, result.std_dev, client.get_goal_status_text()), flush=True)
