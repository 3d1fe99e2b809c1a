"""visualization_msgs: Marker and MarkerArray (ROS 2 Humble), what rviz draws by topic."""

from __future__ import annotations

from typing import ClassVar

from pydantic import ConfigDict, Field

from shared_models._message import Bool, Float32, Int32, Message, String, UInt8Array
from shared_models.builtin_interfaces import Duration
from shared_models.geometry_msgs import Point, Pose, Vector3
from shared_models.sensor_msgs import CompressedImage
from shared_models.std_msgs import ColorRGBA, Header

__all__ = ["Marker", "MarkerArray", "MeshFile", "UVCoordinate"]


class UVCoordinate(Message):
    """A texture coordinate of a marker's vertex, each in 0..1."""

    __ros_type__ = "visualization_msgs/msg/UVCoordinate"
    __ros_comment__ = (
        "# Location of the pixel as a ratio of the width of a 2D texture.\n"
        "# Values should be in range: [0.0-1.0]."
    )

    u: Float32 = 0.0
    v: Float32 = 0.0


class MeshFile(Message):
    """A mesh file carried inside a marker; ``data`` travels in JSON as base64."""

    model_config = ConfigDict(ser_json_bytes="base64", val_json_bytes="base64")

    __ros_type__ = "visualization_msgs/msg/MeshFile"
    __ros_comment__ = "# Used to send raw mesh files."

    filename: String = ""  # also gives the file extension for the parser
    data: UInt8Array = b""  # the raw contents of the mesh file


class Marker(Message):
    """A shape for rviz to draw: ``type`` and ``action`` take the class's constants.

    Example::

        Marker(
            header=Header(frame_id="odom"), ns="goal", id=0,
            type=Marker.SPHERE, action=Marker.ADD,
            pose=Pose(position=Point(x=1.0, y=2.0)),
            scale=Vector3(x=0.2, y=0.2, z=0.2), color=ColorRGBA(r=1.0, a=1.0),
        )

    The defaults are ROS's: a zero scale and a fully transparent colour, so a marker needs both
    set to be seen.
    """

    __ros_type__ = "visualization_msgs/msg/Marker"
    __ros_comment__ = (
        "# See:\n"
        "#  - http://www.ros.org/wiki/rviz/DisplayTypes/Marker\n"
        "#  - http://www.ros.org/wiki/rviz/Tutorials/Markers%3A%20Basic%20Shapes\n"
        "#\n"
        "# for more information on using this message with rviz."
    )
    __ros_constants__ = (
        "ARROW",
        "CUBE",
        "SPHERE",
        "CYLINDER",
        "LINE_STRIP",
        "LINE_LIST",
        "CUBE_LIST",
        "SPHERE_LIST",
        "POINTS",
        "TEXT_VIEW_FACING",
        "MESH_RESOURCE",
        "TRIANGLE_LIST",
        "ADD",
        "MODIFY",
        "DELETE",
        "DELETEALL",
    )

    ARROW: ClassVar[Int32] = 0
    CUBE: ClassVar[Int32] = 1
    SPHERE: ClassVar[Int32] = 2
    CYLINDER: ClassVar[Int32] = 3
    LINE_STRIP: ClassVar[Int32] = 4
    LINE_LIST: ClassVar[Int32] = 5
    CUBE_LIST: ClassVar[Int32] = 6
    SPHERE_LIST: ClassVar[Int32] = 7
    POINTS: ClassVar[Int32] = 8
    TEXT_VIEW_FACING: ClassVar[Int32] = 9
    MESH_RESOURCE: ClassVar[Int32] = 10
    TRIANGLE_LIST: ClassVar[Int32] = 11

    ADD: ClassVar[Int32] = 0
    MODIFY: ClassVar[Int32] = 0
    DELETE: ClassVar[Int32] = 2
    DELETEALL: ClassVar[Int32] = 3

    header: Header = Field(default_factory=Header)  # header for time/frame information
    ns: String = ""  # namespace to place this object in, used with id to make a unique name
    id: Int32 = 0  # object id, unique within its namespace
    type: Int32 = 0  # type of object (ARROW, CUBE, ...)
    action: Int32 = 0  # ADD/MODIFY, DELETE or DELETEALL
    pose: Pose = Field(default_factory=Pose)  # pose of the object
    scale: Vector3 = Field(default_factory=Vector3)  # 1,1,1 is 1 m on a side
    color: ColorRGBA = Field(default_factory=ColorRGBA)  # each channel 0-1
    lifetime: Duration = Field(default_factory=Duration)  # how long to last; 0 is forever
    frame_locked: Bool = False  # follow its frame as it moves (rather than stay where it was put)
    points: list[Point] = Field(default_factory=list)  # for POINTS, LINE_STRIP, ..._LIST types
    colors: list[ColorRGBA] = Field(default_factory=list)  # 0, or one per point
    texture_resource: String = ""  # a texture's URI, or "embedded://name" to use `texture`
    texture: CompressedImage = Field(default_factory=CompressedImage)
    uv_coordinates: list[UVCoordinate] = Field(default_factory=list)  # one per vertex, 0-1
    text: String = ""  # only used for TEXT_VIEW_FACING
    mesh_resource: String = ""  # only used for MESH_RESOURCE; "embedded://name" uses mesh_file
    mesh_file: MeshFile = Field(default_factory=MeshFile)
    mesh_use_embedded_materials: Bool = False


class MarkerArray(Message):
    """Several markers in one message (rviz draws them all)."""

    __ros_type__ = "visualization_msgs/msg/MarkerArray"

    markers: list[Marker] = Field(default_factory=list)
