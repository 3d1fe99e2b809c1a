"""The workshop's perception task: the boxes from the simulator, orientation dropped."""

from services.runtime import Node, spin
from shared_models.geometry_msgs import Point32, Polygon, PoseArray


class MyPerception(Node):
    def __init__(self):
        super().__init__("perception")
        self.boxes_message = PoseArray()
        self.create_subscription(PoseArray, "/simulator/boxes", self.callback, 1)
        self.publisher = self.create_publisher(Polygon, "perception/boxes", 1)
        self.create_timer(0.1, self.run_loop)

    def callback(self, message):
        self.boxes_message = message

    def run_loop(self):
        polygon_message = Polygon()
        for pose in self.boxes_message.poses:
            point = Point32(x=pose.position.x, y=pose.position.y, z=pose.position.z)
            polygon_message.points.append(point)
        self.publisher.publish(polygon_message)


if __name__ == "__main__":
    spin(MyPerception())
