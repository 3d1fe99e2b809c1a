#!/usr/bin/env python3
# AI: takes off, flies over every box (always to the nearest one not visited yet), then flies
# back to where it took off and lands there.
import math

import rospy
from geometry_msgs.msg import Polygon, PoseStamped
from ros_workshop.srv import FlyCommand, FlyCommandResponse
from std_srvs.srv import Trigger, TriggerResponse

boxes = []
drone_position = None


def handleBoxes(message):
    global boxes
    boxes = message.points


def handlePose(message):
    global drone_position
    drone_position = message.pose.position


def sendTakeOffCommand():
    take_off_service_topic = "/control/take_off"
    # In case the Control node isn't ready yet, we wait until it is ready to receive commands.
    rospy.wait_for_service(take_off_service_topic) 
    #  We want to wrap the service call in a try/catch since it can fail and raise a ServiceException
    try:
        # Think of this as creating a take off function we can call
        take_off = rospy.ServiceProxy(take_off_service_topic, Trigger)
        # We then call this function and get the response from the control node
        take_off_response = take_off()
		
        # Do something with the response, for example check the status flag 
        if take_off_response.success:
            rospy.loginfo("Take off successfully sent to Control node! Got response: %s", take_off_response.message)
        else:
            rospy.logerr("Oh no! The Control node responded with an error: %s", take_off_response.message)

    except rospy.ServiceException as exception:
        rospy.logerr("Service class failed: %s", exception)


def sendFlyCommand(x, y):
    fly_service_topic = "/control/fly"
    rospy.wait_for_service(fly_service_topic)
    try:
        fly = rospy.ServiceProxy(fly_service_topic, FlyCommand)
        fly_response = fly(x, y)
        if fly_response.success:
            rospy.loginfo("Fly command sent! Got response: %s", fly_response.message)
        else:
            rospy.logerr("Control did not want to fly: %s", fly_response.message)
        return fly_response.success
    except rospy.ServiceException as exception:
        rospy.logerr("Service call failed: %s", exception)
        return False


def sendLandCommand():
    rospy.wait_for_service("/control/land")
    try:
        land = rospy.ServiceProxy("/control/land", Trigger)
        land_response = land()
        rospy.loginfo("Land command sent, got: %s", land_response.message)
        return land_response.success
    except rospy.ServiceException as exception:
        rospy.logerr("Service call failed: %s", exception)
        return False


def distance(a, b):
    # Pythagoras, on the ground
    return math.sqrt((a.x - b.x) ** 2 + (a.y - b.y) ** 2)


rospy.init_node("ai")
rospy.Subscriber("/perception/boxes", Polygon, handleBoxes)
rospy.Subscriber("/drone/pose", PoseStamped, handlePose)
visit_radius = rospy.get_param("~visit_radius", 0.3)
rospy.loginfo("Visiting each box within %.2f m", visit_radius)

rate = rospy.Rate(10)
# Wait until we know where we are and where the boxes are
while not rospy.is_shutdown() and (drone_position is None or len(boxes) == 0):
    rate.sleep()

home = drone_position
sendTakeOffCommand()

visited = []
target = None
fly_command_sent = False
land_command_sent = False
while not rospy.is_shutdown():
    rate.sleep()
    if drone_position.z < 2.5 and not land_command_sent:
        continue  # still taking off

    if target is None:
        not_visited = [i for i in range(len(boxes)) if i not in visited]
        if not_visited:
            # Bonus: the nearest box next
            target_index = min(not_visited, key=lambda i: distance(boxes[i], drone_position))
            target = boxes[target_index]
        else:
            target = home
        fly_command_sent = False

    if not fly_command_sent:
        fly_command_sent = sendFlyCommand(target.x, target.y)
        continue

    if distance(target, drone_position) < visit_radius:
        if target is home:
            if not land_command_sent:
                land_command_sent = sendLandCommand()
            elif drone_position.z <= 0.1:
                rospy.loginfo("Mission complete: visited %d boxes and landed", len(visited))
                rospy.signal_shutdown("mission complete")
        else:
            visited.append(target_index)
            rospy.loginfo("Visited box %d at (%.2f, %.2f)", len(visited), target.x, target.y)
            target = None
