"""Types this process does not know, learned from the core.

A node registers the definition files of its own types (``NodeDescription.interfaces``); the
core builds them and hands them on at ``GET /api/interfaces/NAME`` (``definitions``). A process
that meets such a type by name only (the recorder reading the graph, the CLI given a type) asks
the core once and builds the same classes::

    if not is_known(name):
        learn_reply(await http.get(core_url + interface_path(name), timeout_s=2.0))
"""

from __future__ import annotations

import logging
from typing import Any
from urllib.parse import quote

from shared_models import UnknownInterfaceError, get_interface
from shared_models.definitions.errors import DefinitionConflict, DefinitionError
from shared_models.definitions.loader import learn_definitions

__all__ = ["interface_path", "is_known", "learn_definitions_reply"]

logger = logging.getLogger("skydeck.runtime")


def is_known(type_name: str) -> bool:
    """Whether this process has the type (its package loaded if need be)."""
    try:
        get_interface(type_name)
    except UnknownInterfaceError:
        return False
    return True


def interface_path(type_name: str) -> str:
    """The core's path that describes ``type_name``."""
    return "/api/interfaces/" + quote(type_name.strip("/"), safe="/")


def learn_definitions_reply(status: int, body: Any) -> bool:
    """Build the types of a ``/api/interfaces/NAME`` reply; whether it held any. A definition
    that cannot be built here is logged (the type stays unknown, as it was)."""
    if status != 200 or not isinstance(body, dict) or not isinstance(body.get("definitions"), dict):
        return False
    try:
        learn_definitions(body["definitions"], source="the core")
    except (DefinitionError, DefinitionConflict) as error:
        logger.warning("cannot use the core's definition of %s: %s", body.get("name"), error)
        return False
    return True
