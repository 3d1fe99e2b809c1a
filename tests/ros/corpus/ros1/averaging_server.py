#! /usr/bin/env python
# A SimpleActionServer in goal callback mode, as the actionlib tutorial's averaging server is
# written: the goal and preempt callbacks, accept_new_goal(), and the work done in a callback of
# its own (here a timer taking one sample each tick: 1, 2, 3, ...).
import math

import rospy

import actionlib

import actionlib_tutorials.msg


class AveragingAction(object):

    def __init__(self, name):
        self._action_name = name
        self._as = actionlib.SimpleActionServer(self._action_name, actionlib_tutorials.msg.AveragingAction, auto_start=False)
        self._as.register_goal_callback(self.goal_cb)
        self._as.register_preempt_callback(self.preempt_cb)
        self._feedback = actionlib_tutorials.msg.AveragingFeedback()
        self._result = actionlib_tutorials.msg.AveragingResult()
        self._as.start()
        rospy.Timer(rospy.Duration(1.0 / rospy.get_param('~rate', 20)), self.sample_cb)

    def goal_cb(self):
        self._data_count = 0
        self._sum = 0.0
        self._sum_sq = 0.0
        self._goal = self._as.accept_new_goal()
        rospy.loginfo('%s: accepted a goal of %d samples' % (self._action_name, self._goal.samples))

    def preempt_cb(self):
        rospy.loginfo('%s: Preempted' % self._action_name)
        self._as.set_preempted()

    def sample_cb(self, event):
        if not self._as.is_active():
            return
        self._data_count += 1
        sample = float(self._data_count)
        self._sum += sample
        self._sum_sq += sample * sample
        self._feedback.sample = self._data_count
        self._feedback.data = sample
        self._feedback.mean = self._sum / self._data_count
        self._feedback.std_dev = math.sqrt(max(0.0, self._sum_sq / self._data_count - self._feedback.mean ** 2))
        self._as.publish_feedback(self._feedback)
        if self._data_count >= self._goal.samples:
            self._result.mean = self._feedback.mean
            self._result.std_dev = self._feedback.std_dev
            if self._result.mean < 5.0:
                rospy.loginfo('%s: Aborted' % self._action_name)
                self._as.set_aborted(self._result)
            else:
                rospy.loginfo('%s: Succeeded' % self._action_name)
                self._as.set_succeeded(self._result)


if __name__ == '__main__':
    rospy.init_node('averaging')
    AveragingAction(rospy.get_name())
    rospy.spin()
