"""A node with parameters, run by the tests as a user would: ``skydeck run tuned_node.py --ros-args ...``."""

from services.runtime import Node, spin
from shared_models.rcl_interfaces import (
    FloatingPointRange,
    ParameterDescriptor,
    SetParametersResult,
)


class TunedNode(Node):
    def __init__(self, settings=None) -> None:
        super().__init__("tuned", settings=settings)
        speed_range = FloatingPointRange(from_value=0.0, to_value=2.0)
        self.declare_parameter("speed", 0.3, ParameterDescriptor(description="m/s", floating_point_range=[speed_range]))
        self.declare_parameter("robot", "robot1")
        self.declare_parameter("flags", [1, 2])
        self.declare_parameter("gains.p", 1.0)
        self.declare_parameter("frozen", 7, ParameterDescriptor(read_only=True))
        self.add_on_set_parameters_callback(self.check)

    def check(self, parameters):
        for parameter in parameters:
            if parameter.name == "robot" and parameter.value == "evil":
                return SetParametersResult(successful=False, reason="no evil robots here")
        return SetParametersResult(successful=True)


if __name__ == "__main__":
    spin(TunedNode())
