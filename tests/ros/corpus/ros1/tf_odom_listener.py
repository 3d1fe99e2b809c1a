#!/usr/bin/env python3
""" Drive an arc and follow the robot with tf (ROS 1), and a carrot broadcast ahead of it """
import rospy
import tf
import tf2_ros
from geometry_msgs.msg import Twist

rospy.init_node('tf_odom_listener')

listener = tf.TransformListener()
broadcaster = tf.TransformBroadcaster()
tf_buffer = tf2_ros.Buffer()
tf2_listener = tf2_ros.TransformListener(tf_buffer)
cmd_vel = rospy.Publisher('cmd_vel', Twist, queue_size=10)

listener.waitForTransform('/odom', '/base_link', rospy.Time(0), rospy.Duration(10.0))
print('READY', flush=True)

try:
    listener.waitForTransform('/odom', '/nowhere', rospy.Time(0), rospy.Duration(0.5))
except tf.Exception as e:
    print('WAITED', e, flush=True)

rate = rospy.Rate(5)
while not rospy.is_shutdown():
    twist = Twist()
    twist.linear.x = 0.2
    twist.angular.z = -0.4
    cmd_vel.publish(twist)
    try:
        (trans, rot) = listener.lookupTransform('/odom', '/base_link', rospy.Time(0))
    except (tf.LookupException, tf.ConnectivityException, tf.ExtrapolationException):
        continue
    now = listener.getLatestCommonTime('/odom', '/base_link')
    roll, pitch, yaw = tf.transformations.euler_from_quaternion(rot)
    print('LATEST', '%d.%09d' % (now.secs, now.nsecs), trans[0], trans[1], yaw, flush=True)

    # a carrot half a metre ahead of the robot, at the same time, read back through odom
    broadcaster.sendTransform((0.5, 0.0, 0.0), tf.transformations.quaternion_from_euler(0, 0, 0),
                              now, 'carrot', 'base_link')
    try:
        carrot = tf_buffer.lookup_transform('odom', 'carrot', now, rospy.Duration(1.0))
        print('CARROT', '%d.%09d' % (now.secs, now.nsecs),
              carrot.transform.translation.x, carrot.transform.translation.y, flush=True)
    except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as e:
        rospy.logwarn('no carrot yet: %s', e)
    rate.sleep()
