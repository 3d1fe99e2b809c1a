"""``ament_index_python`` and ``ament_index_python.packages``: a package's share directory, in
the workspace of the launch being read (its source folder: services.launch.ros2.packages)."""

import sys

from services.launch.ros2.api import unprovided
from services.launch.ros2.packages import PackageNotFoundError
from services.launch.ros2.places import caller_place, current_workspace


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    """The package's share directory; PackageNotFoundError (one line, the user's line) if none."""
    try:
        return str(current_workspace().share_directory(package_name))
    except PackageNotFoundError as error:
        raise PackageNotFoundError(f"{caller_place()}: {error}") from None


packages = sys.modules[__name__]  # ament_index_python.packages

__all__ = ["PackageNotFoundError", "get_package_share_directory", "packages"]
__getattr__ = unprovided("ament_index_python", __all__)
