"""The ROS 2 bridge: Skydeck on a DDS domain, topics and services both ways (``skydeck bridge ros2``)."""
