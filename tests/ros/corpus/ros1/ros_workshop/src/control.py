#!/usr/bin/env python3
# Control: takes off, flies and lands the drone when the AI asks, by streaming a position
# setpoint to the drone 30 times a second (what MAVROS needs to stay in offboard mode).
import rospy
from geometry_msgs.msg import Point, PoseStamped
from mavros_msgs.msg import PositionTarget
from ros_workshop.srv import FlyCommand, FlyCommandRequest, FlyCommandResponse
from std_srvs.srv import Trigger, TriggerResponse, TriggerRequest

drone_position = Point()

setpoint = PositionTarget()
setpoint.header.frame_id = "map"
setpoint.coordinate_frame = PositionTarget.FRAME_LOCAL_NED
# Only the position counts: ignore the velocity, acceleration and yaw rate fields
setpoint.type_mask = (
    PositionTarget.IGNORE_VX | PositionTarget.IGNORE_VY | PositionTarget.IGNORE_VZ
    | PositionTarget.IGNORE_AFX | PositionTarget.IGNORE_AFY | PositionTarget.IGNORE_AFZ
    | PositionTarget.IGNORE_YAW_RATE
)


def handlePose(message):
    global drone_position
    drone_position = message.pose.position


def handleTakeOffRequest(request):
    response = TriggerResponse()	
    
    rospy.loginfo("Handling take off!")
    # If the drone is at ground
    if drone_position.z <= 0.1:
        response.success = True
        response.message = "All ok!"

        # Set the take off position to 3 m in air from the current position
        setpoint.position.x = drone_position.x
        setpoint.position.y = drone_position.y
        setpoint.position.z = 3.0
    else:
        response.success = False 
        response.message = "Seems like the drone is already flying!"
	
    return response


def handleFlyRequest(request):
    response = FlyCommandResponse()
    # Only fly once we are up in the air
    if drone_position.z < 2.0:
        response.success = False
        response.message = "Take off first, the drone is not in the air!"
        return response

    setpoint.position.x = request.x
    setpoint.position.y = request.y
    rospy.loginfo("Flying to (%.2f, %.2f)", request.x, request.y)
    response.success = True
    response.message = "Flying to (%.2f, %.2f)" % (request.x, request.y)
    return response


def handleLandRequest(request):
    if drone_position.z <= 0.1:
        return False, "The drone is already on the ground!"
    rospy.loginfo("Landing at (%.2f, %.2f)", drone_position.x, drone_position.y)
    setpoint.position.x = drone_position.x
    setpoint.position.y = drone_position.y
    setpoint.position.z = 0.0
    return True, "Landing"


rospy.init_node("control")
rospy.Subscriber("/drone/pose", PoseStamped, handlePose)
setpoint_publisher = rospy.Publisher("/drone/setpoint", PositionTarget, queue_size=1)

# Before main loop
take_off_service = rospy.Service("/control/take_off", Trigger, handleTakeOffRequest)
fly_service = rospy.Service("/control/fly", FlyCommand, handleFlyRequest)
land_service = rospy.Service("/control/land", Trigger, handleLandRequest)

rate = rospy.Rate(rospy.get_param("~rate", 30))
while not rospy.is_shutdown():
    setpoint.header.stamp = rospy.Time.now()
    setpoint_publisher.publish(setpoint)
    rate.sleep()
