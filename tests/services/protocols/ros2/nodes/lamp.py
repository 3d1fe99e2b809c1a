"""An unmodified rclpy service server: /lamp/set (std_srvs/SetBool)."""

import rclpy
from rclpy.node import Node
from std_srvs.srv import SetBool


def main():
    rclpy.init()
    node = Node("lamp")

    def set_lamp(request, response):
        response.success = True
        response.message = "lamp " + ("on" if request.data else "off")
        return response

    node.create_service(SetBool, "/lamp/set", set_lamp)
    print("serving", flush=True)
    rclpy.spin(node)


if __name__ == "__main__":
    main()
