"""The root of every exception Skydeck raises on purpose, and how the edges map them.

It lives in the lowest package so that messages, the SDK, the core, the simulator, the
launcher and the CLI all descend from one class. The whole tree::

    SkydeckError                          http  close  raised when
    ├── InvalidNameError (ValueError)      404  1008   a topic/service/node name is not a ROS name
    ├── UnknownInterfaceError (LookupError)404  1008   a type name no message or service has
    ├── DefinitionError (ValueError)       422  1008   a .msg/.srv/.action file cannot be read (file:line)
    ├── DefinitionConflict (ValueError)    409  1008   another version of a type this process holds
    ├── FrameRejected                       -   its own  a client's frame or option cannot be taken
    ├── NodeError                          500  1011   a node used in a way it cannot honour
    ├── ParameterException                 400   -     a parameter used in a way the node cannot honour
    │   └── (rclpy's names: ParameterNotDeclaredException, InvalidParameterValueException, ...)
    ├── RosArgumentsError                  400   -     a --ros-args argument or params file is wrong
    ├── ServiceError                       502   -     a service call got no answer
    │   ├── ServiceUnavailableError        503   -     nobody hosts it / its node is unreachable
    │   ├── ServiceTimeoutError            504   -     its node did not answer in time
    │   ├── ServiceCallRejectedError       4xx   -     its node refused the request
    │   └── ServiceCallFailed              its   -     a call through the core reached no service
    ├── ServiceHandlerError                500   -     a handler raised or returned the wrong type
    ├── GoalTransitionError                 -    -     an action goal moved as ROS 2's state machine forbids
    ├── RegistrationRejected                -    -     the core refused a node's session
    ├── ClassTokensError                   400   -     a roster name, tokens file or class rules file that cannot be used
    ├── AccessRefused                      403  1008   a class's fences: the subject may not (services/access/policy.py)
    │   ├── Forbidden                      403  1008   the subject's token may not do this
    │   └── TokenNeeded                    401  1008   no token (or one nobody has) where one is needed
    ├── RateLimited                        429  4002   a student's token sends too much, or has too many calls waiting
    ├── EndpointPortBusy                    -    -     a protocol endpoint's port is taken at start-up
    ├── Refused (rosbridge), _Refused (Foxglove)  a protocol op that cannot be done: a status reply
    ├── ParameterError                     400   -     a parameter a protocol client named or set is wrong
    ├── HttpError                           -    -     an internal HTTP request got no reply
    │   ├── HttpTimeout / HttpUnreachable
    ├── InvalidCommand (ValueError)         -    -     a setpoint or cmd_vel the physics refuses
    ├── UnknownWorld (LookupError)          -    -     a world name the table of worlds does not have
    ├── GlUnavailable (RuntimeError)        -    -     no OpenGL for the camera (it falls back to PyBullet's renderer)
    ├── LaunchError                         -    -     a launch cannot go ahead
    │   └── LaunchFileError                            the launch file is missing or wrong
    ├── PackageNotFound (LookupError)       -    -     a roslaunch file's package or node type is not there
    ├── RosParamError                       -    -     ROS 1's parameter server refused or did not answer
    ├── RosFacadeError                      -    -     a ROS program asked for what Skydeck lacks (services/ros/errors.py)
    ├── ROSException, ROSInternalException  -    -     rospy's own (services/ros/rospy/exceptions.py)
    ├── TransformException                  -    -     tf2's, with its subclasses (services/ros/tf2_ros/exceptions.py)
    ├── TypeException (TypeError)           -    -     Buffer.transform of an unregistered type (tf2_ros)
    ├── CvBridgeError (TypeError)           -    -     an image cv_bridge cannot convert (services/ros/cv_bridge/)
    ├── HighGuiError (cv2.error)            -    -     an OpenCV window call Skydeck cannot honour (services/ros/highgui/)
    ├── CdrError (ValueError)               -    -     a value that does not fit its CDR, or bytes that are no message (shared_models/cdr.py)
    ├── NotBridged, TypeNotAvailable        -    -     a type the ROS 2 bridge cannot carry (services/protocols/ros2/)
    ├── BuildFailed                         -    -     a ROS 2 interface package did not build (its cmake output's tail)
    ├── BridgeUnavailable                   -    -     `skydeck bridge ros2` cannot start here (the extra, an option)
    ├── CliError                            -    -     a CLI command the user can fix
    └── BenchError                          -    -     a benchmark could not be measured

Each class says what happened and what to do in its message. The edges map them in one place
each: HTTP handlers answer ``error.http_status`` with ``{"detail": str(error)}``, WebSocket
handlers close with ``error.close_code``, and the CLI prints ``skydeck: error: <message>`` and
exits 1, for any ``SkydeckError``.
"""

from __future__ import annotations

from typing import ClassVar

from shared_models.close_codes import Close

__all__ = ["SkydeckError"]


class SkydeckError(Exception):
    """Base class of every exception Skydeck raises on purpose; the message says what to do."""

    # How the HTTP and WebSocket edges answer this error when it reaches them.
    http_status: ClassVar[int] = 500
    close_code: ClassVar[int] = Close.INTERNAL
