"""A safety stop in rospy, as a ROS 1 student writes it: a Rate loop, a subscriber thread."""

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

ahead = [None]


def on_scan(msg):
    if msg.ranges[0] != 0.0:
        ahead[0] = msg.ranges[0]


rospy.init_node("rospy_estop")
rospy.Subscriber("scan", LaserScan, on_scan)
publisher = rospy.Publisher("cmd_vel", Twist, queue_size=10)
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    command = Twist()
    if ahead[0] is not None and ahead[0] > 0.6:
        command.linear.x = 0.2
    publisher.publish(command)
    rate.sleep()
