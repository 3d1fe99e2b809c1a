"""ROS 1's parameter server, held by the core (roscore holds it in ROS 1).

    PUT    /api/rosparam/ai/visit_radius   {"value": 0.4}   set (a mapping sets a whole subtree)
    GET    /api/rosparam/ai/visit_radius                    {"name": "/ai/visit_radius", "value": 0.4}
    GET    /api/rosparam/ai                                 {"name": "/ai", "value": {"visit_radius": 0.4}}
    GET    /api/rosparam                                    the whole tree
    DELETE /api/rosparam/ai/visit_radius

ROS 1 parameters are global: one tree of names, a namespace read as a mapping of what is under
it. rospy's ``get_param``/``set_param`` (:mod:`services.ros.rospy.params`) and the launch of a
roslaunch file's ``<param>``/``<rosparam>`` use it; names arrive resolved (absolute). ROS 2
parameters are not here: they belong to each node (``skydeck param``). The tree lives as long
as the core process, as roscore's does. Values are what XML-RPC carried: booleans, integers,
floats, strings, lists of those, and mappings (namespaces); there is no null.
"""

from __future__ import annotations

import copy
from typing import Annotated, Any

from fastapi import APIRouter, Depends, HTTPException, Request
from pydantic import BaseModel, StringConstraints

from services.access import Verb
from services.core.visitors import FENCED, VisitorDep, require
from services.runtime.rosparam import PARAMETER_TOKEN, check_parameter_value, parameter_tokens

__all__ = ["ParameterTree", "router"]



class ParameterTree:
    """The parameter server's tree (see the module docstring); absolute names, ``/`` the root."""

    def __init__(self) -> None:
        self._root: dict[str, Any] = {}

    def get(self, name: str) -> Any:
        """The value at ``name`` (a copy of the mapping for a namespace); KeyError if unset."""
        node: Any = self._root
        for token in parameter_tokens(name):
            if not isinstance(node, dict) or token not in node:
                raise KeyError(name)
            node = node[token]
        return copy.deepcopy(node)

    def set(self, name: str, value: Any) -> None:
        """Set ``name`` to ``value``; a mapping replaces the subtree at ``name``, and a value
        set under a name that held a plain value turns that name into a namespace."""
        check_parameter_value(value, name)
        tokens = parameter_tokens(name)
        if not tokens:
            if not isinstance(value, dict):
                raise ValueError("the root / can only be set to a mapping of names to values")
            self._root = copy.deepcopy(value)
            return
        node = self._root
        for token in tokens[:-1]:
            if not isinstance(node.get(token), dict):
                node[token] = {}
            node = node[token]
        node[tokens[-1]] = copy.deepcopy(value)

    def delete(self, name: str) -> None:
        """Forget ``name`` and all under it; KeyError if unset."""
        tokens = parameter_tokens(name)
        if not tokens:
            self._root = {}
            return
        node: Any = self._root
        for token in tokens[:-1]:
            if not isinstance(node, dict) or token not in node:
                raise KeyError(name)
            node = node[token]
        if not isinstance(node, dict) or tokens[-1] not in node:
            raise KeyError(name)
        del node[tokens[-1]]


# -- the API ------------------------------------------------------------------------------------

router = APIRouter(prefix="/api/rosparam", tags=["ROS 1 parameters"])


class ParameterValue(BaseModel):
    """A parameter's value: a number, bool, string, list, or mapping (a namespace)."""

    value: Any


class NamedValue(ParameterValue):
    """A parameter and its absolute name."""

    name: str


def _tree(request: Request) -> ParameterTree:
    return request.app.state.rosparam  # type: ignore[no-any-return]


TreeDep = Annotated[ParameterTree, Depends(_tree)]

# A parameter's name under /api/rosparam/: the tokens parameter_tokens takes, between slashes. In
# the schema, so that clients (and the fuzzer) know what a valid name is; the tree then meets
# only valid names, and its ValueError is about a value.
ParameterName = Annotated[str, StringConstraints(pattern=rf"^{PARAMETER_TOKEN}(/+{PARAMETER_TOKEN})*/*$")]

# A name that is not a ROS name is a 422 like any other invalid input; an unset one is a 404.
_BAD_NAME: dict[int | str, dict[str, Any]] = {422: {"description": "Not a ROS parameter name (letters, digits and _ between slashes)"}}
_BAD_VALUE: dict[int | str, dict[str, Any]] = {
    422: {"description": "Not a ROS parameter name, or not a parameter value (null; a key that is not a name)"}
}
_UNSET: dict[int | str, dict[str, Any]] = {404: {"description": "No such parameter"}}


@router.get("", responses=FENCED | _UNSET | _BAD_NAME)
@router.get("/{name:path}", responses=FENCED | _UNSET | _BAD_NAME)
async def get_parameter(tree: TreeDep, visitor: VisitorDep, name: ParameterName = "") -> NamedValue:
    """A parameter's value; a namespace's is the mapping of what is under it."""
    full = "/" + name.strip("/")
    require(visitor, Verb.READ, full)
    try:
        return NamedValue(name=full, value=tree.get(full))
    except KeyError:
        raise HTTPException(404, f"no parameter {full}: see GET /api/rosparam for all") from None


@router.put("", responses=FENCED | _BAD_VALUE)
@router.put("/{name:path}", responses=FENCED | _BAD_VALUE)
async def set_parameter(body: ParameterValue, tree: TreeDep, visitor: VisitorDep, name: ParameterName = "") -> NamedValue:
    """Set a parameter (a mapping sets the whole namespace under the name)."""
    full = "/" + name.strip("/")
    require(visitor, Verb.SET_PARAMETER, full)
    try:
        tree.set(full, body.value)
    except ValueError as error:
        raise HTTPException(422, str(error)) from None
    return NamedValue(name=full, value=body.value)


@router.delete("/{name:path}", responses=FENCED | _UNSET | _BAD_NAME)
async def delete_parameter(tree: TreeDep, visitor: VisitorDep, name: ParameterName) -> NamedValue:
    """Delete a parameter and everything under it; the answer holds what was deleted."""
    full = "/" + name.strip("/")
    require(visitor, Verb.SET_PARAMETER, full)
    try:
        value = tree.get(full)
        tree.delete(full)
    except KeyError:
        raise HTTPException(404, f"no parameter {full}") from None
    return NamedValue(name=full, value=value)
