"""The perception node: boxes from the simulator, orientation dropped."""
