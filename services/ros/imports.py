"""The import finder behind :func:`services.ros.enable_ros_imports`: ROS's module names, inside
processes that ``skydeck run`` starts.

    rclpy, rclpy.node, ...     -> services.ros.rclpy, services.ros.rclpy.node, ... (the same modules)
    rospy                      -> services.ros.rospy
    tf2_ros, tf, ...           -> services.ros.tf2_ros, services.ros.tf, ... (FACADES)
    cv2                        -> the real OpenCV, its HighGUI windows then served by Skydeck (ADAPTED)
    geometry_msgs.msg          -> a view of shared_models.geometry_msgs: its geometry_msgs/msg/* types
    std_srvs.srv               -> its std_srvs/srv/* types, with ROS 1's TriggerRequest/TriggerResponse
                                  and ROS 2's Trigger_Request/Trigger_Response spellings
    example_interfaces.action  -> its actions (Fibonacci, with .Goal, .Result, .Feedback, .Impl)
    my_pkg.msg                 -> the types of my_pkg's msg/*.msg files, loaded on first import,
                                  for a package of definition files Skydeck ships or that is in
                                  the workspace (shared_models.definitions)

One type system: a view's attributes ARE the ``shared_models`` classes. The finder sits first on
``sys.meta_path`` for these names only (inside a Skydeck process Skydeck is the ROS); for any
other name it lets Python's own finders look first, and only when none finds a name that looks
like a ROS package (``foo_msgs``, ``tf2_ros``...) does it answer with one line that says so.
Nothing here is installed in site-packages, so a real ROS in the user's own Python is untouched.
"""

from __future__ import annotations

import dis
import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
from collections.abc import Sequence
from typing import Any

from services.ros.aliases import AliasLoader
from services.ros.errors import (
    NotProvidedImportError,
    UnknownMessageError,
    UnknownMessagePackageError,
    not_provided,
)
from services.ros.extras import EXTRAS, check_extra
from shared_models._message import ActionType, Message, ServiceType, registered
from shared_models.catalogue import MESSAGE_PACKAGES
from shared_models.definitions.index import index
from shared_models.definitions.loader import load_any_package

__all__ = ["ADAPTED", "FACADES", "RosImportFinder", "message_view", "package_names"]

# A ROS Python package's name -> the façade that imitates it.
FACADES = {
    "actionlib": "services.ros.actionlib",  # ROS 1's (its messages, actionlib.msg, are a package's)
    "rclpy": "services.ros.rclpy",
    "rospy": "services.ros.rospy",
    "cv_bridge": "services.ros.cv_bridge",
    "tf": "services.ros.tf",  # ROS 1's (tf.transformations, TransformListener, TransformBroadcaster)
    "tf2_geometry_msgs": "services.ros.tf2_geometry_msgs",
    "tf2_ros": "services.ros.tf2_ros",
    "tf_transformations": "services.ros.tf_transformations",
}
# A real module -> the Skydeck module whose ``install(module)`` adapts it once it has loaded.
ADAPTED = {"cv2": "services.ros.highgui"}  # OpenCV's windows in the dashboard
_KINDS = {"msg": Message, "srv": ServiceType, "action": ActionType}
_KIND_WORDS = {"msg": "messages", "srv": "services", "action": "actions"}
# ROS Python packages a course meets that are not message packages and that Skydeck lacks.
_NOT_PROVIDED = frozenset(
    {
        "ament_index_python",
        "image_geometry",
        "image_transport",
        "laser_geometry",
        "launch",
        "launch_ros",
        "message_filters",
        "rclpy_message_converter",
        "rosbag",
        "rosbag2_py",
        "roslaunch",
        "roslib",
        "rospkg",
        "rosidl_runtime_py",
        "sensor_msgs_py",
    }
)
_PACKAGE_SUFFIXES = ("_msgs", "_srvs", "_interfaces", "_msg", "_srv", "_action")


def _known() -> str:
    return ", ".join([*MESSAGE_PACKAGES, *sorted(package_names() - set(MESSAGE_PACKAGES))])


def package_names() -> set[str]:
    """Every message package this process can import: Skydeck's, and the definition packages
    it ships or finds in the workspace."""
    return set(MESSAGE_PACKAGES) | {package.name for package in index.interface_packages()}


def _is_message_package(name: str) -> bool:
    if name in MESSAGE_PACKAGES:
        return True
    package = index.find(name)
    return package is not None and package.has_interfaces


class _AdaptingLoader(importlib.abc.Loader):
    """Loads a real module with its own loader, then hands it to its adapter's ``install``.
    While it loads, the finder lets that name go by (cv2's loader imports "cv2" again, its
    compiled part, which must be OpenCV's own)."""

    def __init__(self, loader: importlib.abc.Loader, adapter: str, loading: set[str]) -> None:
        self._loader = loader
        self._adapter = adapter
        self._loading = loading

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return self._loader.create_module(spec)

    def exec_module(self, module: types.ModuleType) -> None:
        name = module.__name__
        self._loading.add(name)
        try:
            self._loader.exec_module(module)
        finally:
            self._loading.discard(name)
        importlib.import_module(self._adapter).install(sys.modules.get(name, module))

    def __getattr__(self, name: str) -> Any:  # the rest of the real loader (resource readers)
        return getattr(self._loader, name)


class _ViewLoader(importlib.abc.Loader):
    """Loads a message package (an empty package) or one of its ``msg``/``srv``/``action`` views."""

    def __init__(self, package: str, kind: str | None) -> None:
        self.package = package
        self.kind = kind

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        if self.kind is None:
            module = _PackageModule(spec.name, f"The ROS package {self.package}: its msg, srv and action types.")
            module.__path__ = []
            return module
        return message_view(self.package, self.kind)

    def exec_module(self, module: types.ModuleType) -> None:
        pass


class _PackageModule(types.ModuleType):
    """A message package itself; for a name that is also a ROS API Skydeck lacks (``actionlib``,
    whose ``actionlib.msg`` it has), that API's names are one line saying so."""

    def __getattr__(self, name: str) -> Any:
        if self.__name__ in _NOT_PROVIDED and not name.startswith("__"):
            text = not_provided(f"`{self.__name__}.{name}`")
            if _called_by_import_from(sys._getframe(1)):
                raise NotProvidedImportError(text)
            raise AttributeError(text)
        raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")


class _MessageView(types.ModuleType):
    """``X.msg`` or ``X.srv``: the package's types; an unknown capitalised name is one clear line."""

    _skydeck_package: str

    def __getattr__(self, name: str) -> Any:
        if not name[:1].isupper():
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")
        known = ", ".join(sorted(n for n in vars(self) if n[:1].isupper()))
        text = f"`{self.__name__}` has no type {name!r} in Skydeck; it has: {known or 'none'}"
        # `from std_msgs.msg import Foo` turns an AttributeError into Python's vaguer "cannot
        # import name"; there we raise the ImportError ourselves. Anywhere else (hasattr,
        # getattr with a default) it must stay an AttributeError.
        if _called_by_import_from(sys._getframe(1)):
            raise UnknownMessageError(text)
        raise AttributeError(text)


_IMPORT_FROM = dis.opmap["IMPORT_FROM"]


def _called_by_import_from(frame: types.FrameType) -> bool:
    code = frame.f_code.co_code
    return 0 <= frame.f_lasti < len(code) and code[frame.f_lasti] == _IMPORT_FROM


def message_view(package: str, kind: str) -> types.ModuleType:
    """The module ``package.kind`` (``geometry_msgs.msg``): every ``package/kind/*`` type under
    its ROS name (and, for the parts of a service or action, ROS 1's name), from the package's
    module in shared_models or its definition files."""
    load_any_package(package)
    view = _MessageView(f"{package}.{kind}", f"The {package}/{kind} types (views of Skydeck's types).")
    view._skydeck_package = package
    prefix = f"{package}/{kind}/"
    for ros_type, value in sorted(registered(prefix).items()):
        setattr(view, ros_type[len(prefix) :], value)  # Trigger, Trigger_Request
        setattr(view, value.__name__, value)  # TriggerRequest (ROS 1), usually the same
    view.__all__ = sorted(n for n in vars(view) if n[:1].isupper())  # type: ignore[attr-defined]
    if kind != "msg" and not any(isinstance(v, type) and issubclass(v, _KINDS[kind]) for v in vars(view).values()):
        raise UnknownMessageError(f"`{package}` has no {_KIND_WORDS[kind]} in Skydeck (no `{package}.{kind}`)")
    return view


class RosImportFinder(importlib.abc.MetaPathFinder):
    """Maps ROS's module names (see the module docstring); installed once per process."""

    def __init__(self) -> None:
        self._adapting: set[str] = set()  # adapted modules being loaded now

    def find_spec(
        self, fullname: str, path: Sequence[str] | None = None, target: types.ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        top, _, rest = fullname.partition(".")
        if top in EXTRAS and not rest:
            check_extra(top)  # one line if the extra (OpenCV...) is not installed; else on as usual
        if fullname in ADAPTED and fullname not in self._adapting:
            return self._adapted_spec(fullname, path, target)
        if top in FACADES and not (rest.partition(".")[0] in _KINDS and _is_message_package(top)):
            return self._facade_spec(fullname, FACADES[top] + (f".{rest}" if rest else ""))
        if _is_message_package(top):  # (a façade's own messages too: actionlib.msg)
            if not rest and top not in MESSAGE_PACKAGES and self._found_elsewhere(fullname, path, target):
                return None  # a catkin package's own Python module of the same name: its .msg is ours
            return self._view_spec(top, rest)
        looks_like_ros = top in _NOT_PROVIDED or top.endswith(_PACKAGE_SUFFIXES)
        if rest or not looks_like_ros or self._found_elsewhere(fullname, path, target):
            return None  # not ours, or a real module of that name (the user's own): Python's
        if top in _NOT_PROVIDED:
            raise NotProvidedImportError(not_provided(f"`{top}`"))
        raise UnknownMessagePackageError(f"`{top}` is not a message package Skydeck knows; known: {_known()}")

    def _facade_spec(self, fullname: str, target: str) -> importlib.machinery.ModuleSpec:
        try:
            real = importlib.util.find_spec(target)
        except ModuleNotFoundError:
            real = None
        if real is None:
            raise NotProvidedImportError(not_provided(f"`{fullname}`"))
        return importlib.machinery.ModuleSpec(
            fullname, AliasLoader(target), is_package=real.submodule_search_locations is not None
        )

    def _adapted_spec(
        self, fullname: str, path: Sequence[str] | None, target: types.ModuleType | None
    ) -> importlib.machinery.ModuleSpec | None:
        spec = self._spec_elsewhere(fullname, path, target)
        if spec is None or spec.loader is None:
            return spec
        spec.loader = _AdaptingLoader(spec.loader, ADAPTED[fullname], self._adapting)
        return spec

    def _view_spec(self, package: str, kind: str) -> importlib.machinery.ModuleSpec:
        if not kind:
            return importlib.machinery.ModuleSpec(package, _ViewLoader(package, None), is_package=True)
        if kind not in _KINDS and package in _NOT_PROVIDED:  # `from actionlib import SimpleActionClient`
            raise NotProvidedImportError(not_provided(f"`{package}.{kind}`"))
        if kind not in _KINDS:
            raise UnknownMessageError(f"`{package}.{kind}`: a message package has .msg, .srv and .action modules only")
        return importlib.machinery.ModuleSpec(f"{package}.{kind}", _ViewLoader(package, kind))

    def _found_elsewhere(
        self, fullname: str, path: Sequence[str] | None, target: types.ModuleType | None
    ) -> bool:
        return self._spec_elsewhere(fullname, path, target) is not None

    def _spec_elsewhere(
        self, fullname: str, path: Sequence[str] | None, target: types.ModuleType | None
    ) -> importlib.machinery.ModuleSpec | None:
        """What Python's other finders make of ``fullname``."""
        for finder in sys.meta_path:
            if finder is self or not hasattr(finder, "find_spec"):
                continue
            spec = finder.find_spec(fullname, path, target)
            if spec is not None:
                return spec  # type: ignore[no-any-return]
        return None
