"""The ``skydeck`` command line: ROS's verbs (topic, service, node, interface, run, launch)."""
