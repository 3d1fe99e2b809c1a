#!/usr/bin/env python3
# Perception: tells the other nodes where the boxes are, as points on perception/boxes.
import rospy 
from geometry_msgs.msg import PoseArray 
# At the top of the file
from geometry_msgs.msg import PoseArray, Polygon

rospy.init_node("perception")

boxes_message = PoseArray()
def callback(message):
    global boxes_message
    boxes_message = message
    rospy.loginfo("Message received")

rospy.Subscriber("/simulator/boxes", PoseArray, callback)

# Before the main loop
publisher = rospy.Publisher("perception/boxes", Polygon, queue_size=1)

rate = rospy.Rate(10)
while not rospy.is_shutdown():
    # Message is empty but can add points to it using polygon_message.points, which is an list of points
    polygon_message = Polygon() 

    # Hint 1 and 2: one point per box, the box's position
    for i in range(len(boxes_message.poses)):
        point = boxes_message.poses[i].position
        polygon_message.points.append(point);

    publisher.publish(polygon_message);
    rate.sleep()
