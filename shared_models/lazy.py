"""Lazy package exports (PEP 562): a name's module is imported the first time the name is used.

    _HOMES = {"World": "sim_server.drone.world"}
    __getattr__ = lazy_exports(__name__, _HOMES)

A package whose exports pull in heavy libraries (FastAPI, PyBullet) stays cheap for a process
that needs only a light part of it. Keep export names different from submodule names: importing
a submodule sets an attribute of that name on the package, which would hide the export.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(package: str, homes: Mapping[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` that loads ``name`` from the module ``homes[name]``."""

    def __getattr__(name: str) -> Any:
        home = homes.get(name)
        if home is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(home), name)

    return __getattr__
