"""The workshop's AI task: take off, then fly over every box, nearest first, one command each."""

import math

from services.runtime import Node, ServiceException, spin
from shared_models.geometry_msgs import Polygon, PoseStamped
from shared_models.ros_workshop import FlyCommand
from shared_models.std_srvs import Trigger


class MyAi(Node):
    def __init__(self):
        super().__init__("my_ai")
        self.drone_position = None
        self.boxes = []
        self.visited = set()
        self.target = None
        self.take_off_sent = False
        self.create_subscription(PoseStamped, "/drone/pose", self.on_pose, 1)
        self.create_subscription(Polygon, "/perception/boxes", self.on_boxes, 1)
        self.take_off = self.create_client(Trigger, "/control/take_off")
        self.fly = self.create_client(FlyCommand, "/control/fly")
        self.create_timer(0.1, self.run_loop)

    def on_pose(self, message):
        self.drone_position = message.pose.position

    def on_boxes(self, message):
        self.boxes = message.points

    def distance_to(self, box):
        return math.hypot(box.x - self.drone_position.x, box.y - self.drone_position.y)

    async def run_loop(self):
        if self.drone_position is None or not self.boxes:
            return
        try:
            if not self.take_off_sent:
                await self.take_off.wait_for_service()
                response = await self.take_off.call(Trigger.Request())
                self.get_logger().info("take off: %s", response.message)
                self.take_off_sent = True
                return
            if self.drone_position.z < 2.5:
                return  # still climbing
            if self.target is not None:
                if self.distance_to(self.boxes[self.target]) > 0.3:
                    return  # not there yet: don't spam control
                self.visited.add(self.target)
                self.get_logger().info("visited box %d (%d of %d)", self.target, len(self.visited), len(self.boxes))
                self.target = None
            remaining = [i for i in range(len(self.boxes)) if i not in self.visited]
            if not remaining:
                return
            self.target = min(remaining, key=lambda i: self.distance_to(self.boxes[i]))
            box = self.boxes[self.target]
            response = await self.fly.call(FlyCommand.Request(x=box.x, y=box.y))
            self.get_logger().info("fly to box %d: %s", self.target, response.message)
        except ServiceException as exception:
            self.get_logger().error("Service call failed: %s", exception)


if __name__ == "__main__":
    spin(MyAi())
