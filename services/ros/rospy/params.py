"""rospy's parameters: ``get_param``, ``set_param``, ``has_param``, ``delete_param``,
``search_param``, ``get_param_names``, on the core's ROS 1 parameter server.

    rate = rospy.get_param("~rate", 30)          # private: /control/rate
    rospy.set_param("/use_sim_time", True)        # global
    rospy.get_param("gains")                      # relative: in the node's namespace; a mapping

As in ROS 1 the parameters are global, one tree held by the core
(:mod:`services.core.parameter_server`): every node sees what another set, a roslaunch file's
``<param>`` and ``<rosparam>`` put them there, and ``skydeck run x.py _rate:=10`` sets ``~rate``.
Names resolve as rospy resolves them (relative in the node's namespace, ``~`` under its name,
then its remappings). Each call is one request to the core; a core that does not answer is
:class:`~services.ros.rospy.exceptions.CoreUnreachableException`.
"""

from __future__ import annotations

import threading
from collections.abc import Coroutine
from typing import Any, TypeVar

from services.ros.bridge import bridge
from services.ros.rospy.core import get_name, resolve_name
from services.ros.rospy.exceptions import CoreUnreachableException, ROSException
from services.runtime.http_client import HttpClient
from services.runtime.rosparam import RosParamClient, RosParamError, RosParamUnreachable
from services.runtime.settings import node_settings

__all__ = [
    "delete_param",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "has_param",
    "search_param",
    "set_param",
]

T = TypeVar("T")


class _Unspecified:
    def __repr__(self) -> str:
        return "<no default>"


_UNSPECIFIED: Any = _Unspecified()


class _Server:
    """The client of the core's parameter server, on the bridge's loop (made again if the loop
    was, after a shutdown)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._loop: object = None
        self._client: RosParamClient | None = None

    def client(self) -> RosParamClient:
        with self._lock:
            loop = bridge.loop
            if self._client is None or self._loop is not loop:
                settings = node_settings()
                headers = {"Authorization": f"Bearer {settings.token}"} if settings.token else None
                self._client = RosParamClient(HttpClient(headers=headers), settings.core_url)
                self._loop = loop
            return self._client

    def run(self, coroutine: Coroutine[Any, Any, T]) -> T:
        try:
            return bridge.run(coroutine)
        except RosParamUnreachable as error:
            raise CoreUnreachableException(str(error)) from None
        except RosParamError as error:
            raise ROSException(str(error)) from None


_server = _Server()


def _resolved(param_name: str) -> str:
    if not isinstance(param_name, str) or not param_name:
        raise ValueError(f"a parameter name is a non-empty string, got {param_name!r}")
    return resolve_name(param_name)


def get_param(param_name: str, default: Any = _UNSPECIFIED) -> Any:
    """The parameter's value (a namespace's: the mapping under it); ``default`` if it is not
    set, or KeyError when no default is given."""
    name = _resolved(param_name)
    try:
        return _server.run(_server.client().get(name))
    except KeyError:
        if default is _UNSPECIFIED:
            raise KeyError(param_name) from None
        return default


get_param_cached = get_param  # every read asks the core: nothing to go stale


def set_param(param_name: str, param_value: Any) -> None:
    """Set the parameter (a mapping sets the namespace under the name)."""
    name = _resolved(param_name)
    _server.run(_server.client().set(name, _plain(param_value)))


def has_param(param_name: str) -> bool:
    """Whether the parameter (or a namespace of that name) is set."""
    try:
        _server.run(_server.client().get(_resolved(param_name)))
    except KeyError:
        return False
    return True


def delete_param(param_name: str) -> None:
    """Delete the parameter and all under it; KeyError if it is not set."""
    try:
        _server.run(_server.client().delete(_resolved(param_name)))
    except KeyError:
        raise KeyError(param_name) from None


def get_param_names() -> list[str]:
    """Every parameter's full name (the leaves of the tree)."""
    names: list[str] = []
    _leaves(_server.run(_server.client().get("/")), "", names)
    return names


def search_param(param_name: str) -> str | None:
    """The full name of the closest ``param_name``: looked for under the node's own name, then
    in its namespace, then each namespace above it up to the root (ROS 1's searchParam: the
    key's first part is what is matched). None when no namespace has it."""
    if param_name.startswith(("/", "~")):
        name = _resolved(param_name)
        return name if has_param(name) else None
    tree = _server.run(_server.client().get("/"))
    first = param_name.split("/", 1)[0]
    caller = [part for part in get_name().split("/") if part]
    for depth in range(len(caller), -1, -1):
        namespace = caller[:depth]
        if _has(tree, [*namespace, first]):
            return "/" + "/".join([*namespace, param_name.strip("/")])
    return None


def _has(tree: Any, path: list[str]) -> bool:
    for token in path:
        if not isinstance(tree, dict) or token not in tree:
            return False
        tree = tree[token]
    return True


def _leaves(value: Any, prefix: str, names: list[str]) -> None:
    if isinstance(value, dict) and value:
        for key, item in value.items():
            _leaves(item, f"{prefix}/{key}", names)
    elif prefix:
        names.append(prefix)


def _plain(value: Any) -> Any:
    """What XML-RPC would carry: tuples as lists, mappings with string keys."""
    if isinstance(value, tuple | list):
        return [_plain(item) for item in value]
    if isinstance(value, dict):
        return {str(key): _plain(item) for key, item in value.items()}
    return value
