""" Drive in a circle at a speed the 'speed' parameter sets, while running """
import rclpy
from geometry_msgs.msg import Twist
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.node import Node


class ParamDriver(Node):
    def __init__(self):
        super().__init__('param_driver')
        self.declare_parameter('speed', 0.1, ParameterDescriptor(description='forward speed, m/s (0 to 0.3)'))
        self.declare_parameter('turn_rate', 0.5)
        self.add_on_set_parameters_callback(self.check_parameters)
        self.vel_pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.create_timer(0.1, self.run_loop)

    def check_parameters(self, parameters):
        for parameter in parameters:
            if parameter.name == 'speed' and not 0.0 <= parameter.value <= 0.3:
                return SetParametersResult(successful=False, reason='speed must be between 0 and 0.3 m/s')
        for parameter in parameters:
            self.get_logger().info(f'{parameter.name} is now {parameter.value}')
        return SetParametersResult(successful=True)

    def run_loop(self):
        msg = Twist()
        msg.linear.x = self.get_parameter('speed').get_parameter_value().double_value
        msg.angular.z = self.get_parameter('turn_rate').value
        self.vel_pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(ParamDriver())


if __name__ == '__main__':
    main()
