"""``tf.transformations`` (ROS 1): the same functions as ROS 2's ``tf_transformations``."""

from __future__ import annotations

from services.ros.tf_transformations import *  # noqa: F403 (the module's whole API, by its __all__)
from services.ros.tf_transformations import __all__ as __all__  # noqa: PLC0414
from services.ros.tf_transformations import __getattr__ as __getattr__  # noqa: PLC0414
