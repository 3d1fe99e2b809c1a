"""``skydeck run`` in a class: a student's nodes run in the namespace their token gives them.

    SKYDECK_CORE_URL=http://HOST:8000 SKYDECK_TOKEN=TOKEN skydeck run wall_follower.py

Before the program starts, ``skydeck run`` asks the core who its token is (``GET /api/access``).
For a student, say ``alice``, every node of the process runs in ``/alice``, as if started with
``--ros-args -r __ns:=/alice``: the program's relative names (``cmd_vel``, ``scan``) become
hers (``/alice/cmd_vel``), and so does the node's own name. A namespace given by hand
(``-r __ns:=``, ROS 1's ``__ns:=``, ``ROS_NAMESPACE``, a behaviour's ``--namespace``) must be
hers or under it: another student's is refused in one line, before anything runs.

Asking first, rather than being told at registration, is what lets the names be right from the
start: a node resolves its names when it is made, before it reaches the core. If the core
cannot be reached, the program starts as given; the core refuses a node outside the student's
fences when it registers, in one line, all the same.
"""

from __future__ import annotations

import logging

from services.access.policy import Role
from services.cli.errors import CliError
from services.runtime.http_client import HttpError, request_once
from services.runtime.ros_args import RemapRule, RosArguments
from shared_models.names import InvalidNameError, resolve_name

__all__ = ["ask_namespace", "fence_namespace", "given_namespaces"]

logger = logging.getLogger("skydeck.cli")


def ask_namespace(core_url: str, token: str) -> str | None:
    """The namespace the core gives ``token``'s nodes (a student's ``/alice``); None when the token
    is not a student's, there is none, or the core cannot say."""
    if not token:
        return None
    try:
        reply = request_once(
            "GET", core_url.rstrip("/") + "/api/access", timeout_s=3.0, headers={"Authorization": f"Bearer {token}"}
        )
        described = reply.json() if reply.status == 200 else {}
    except (HttpError, ValueError) as error:  # ValueError: a reply that is not JSON
        logger.debug("could not ask the core at %s who the token is: %s", core_url, error)
        return None
    if not isinstance(described, dict) or described.get("role") != Role.STUDENT.value:
        return None
    namespace = described.get("namespace")
    return namespace if isinstance(namespace, str) and namespace.startswith("/") else None


def given_namespaces(arguments: RosArguments, node_argv: list[str], ros_namespace: str) -> list[str]:
    """Every namespace the command line and environment give the nodes: ``__ns`` rules,
    ``ROS_NAMESPACE``, and a behaviour's ``--namespace NS``."""
    given = [rule.target for rule in arguments.remap_rules if rule.source == "__ns"]
    if ros_namespace:
        given.append(ros_namespace)
    for index, word in enumerate(node_argv):
        if word == "--namespace" and index + 1 < len(node_argv):
            given.append(node_argv[index + 1])
        elif word.startswith("--namespace="):
            given.append(word.partition("=")[2])
    return given


def fence_namespace(namespace: str, arguments: RosArguments, given: list[str]) -> RosArguments:
    """``arguments``, with the nodes put in ``namespace`` (a student's); CliError if a namespace
    ``given`` is another's."""
    for text in given:
        try:
            resolved = "/" if text in ("", "/") else resolve_name(text)
        except InvalidNameError as error:
            raise CliError(f"namespace {text!r}: {error}") from None
        if resolved != namespace and not resolved.startswith(namespace + "/"):
            raise CliError(
                f"your token is {namespace.lstrip('/')}'s: your nodes run in {namespace}, not {resolved} "
                f"(leave the namespace out, or give {namespace})"
            )
    if any(rule.source == "__ns" for rule in arguments.remap_rules):
        return arguments
    return arguments + RosArguments(remap_rules=[RemapRule(None, "__ns", namespace)])
