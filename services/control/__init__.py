"""The control node: take-off, fly and land services, and the 30 Hz setpoint stream."""
