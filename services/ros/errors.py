"""What the ROS façades raise when a program asks for something Skydeck does not have.

    SkydeckError
    └── RosFacadeError
        ├── UnknownMessagePackageError (ImportError)   `import foo_msgs.msg`: no such message package
        ├── UnknownMessageError (ImportError)          `from std_msgs.msg import Foo`: no such type
        ├── NotProvidedError (NotImplementedError)     a ROS API the façades do not provide
        │   └── NotProvidedImportError (ImportError)   ... met at an import (`import rclpy.action`)
        ├── SetupFileError                             a package's setup.py/setup.cfg cannot be read
        └── PackageTargetError (LookupError)           `skydeck run PKG EXE`: no such package or executable

Each is printed by ``skydeck run`` as one line (``skydeck: error: ...``), never a traceback into
Skydeck's code; each also is the built-in class a ROS program would catch.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from typing import Any, NoReturn

from shared_models.errors import SkydeckError

__all__ = [
    "NotProvidedError",
    "NotProvidedImportError",
    "RosFacadeError",
    "UnknownMessageError",
    "UnknownMessagePackageError",
    "not_provided",
    "not_provided_attributes",
]

DOCS = "docs/ros.md"


class RosFacadeError(SkydeckError):
    """A ROS program asked the façades for something Skydeck does not have."""


class UnknownMessagePackageError(RosFacadeError, ImportError):
    """An import of a message package Skydeck does not know (``import foo_msgs.msg``)."""


class UnknownMessageError(RosFacadeError, ImportError):
    """An import of a type a known message package does not have (``from std_msgs.msg import Foo``)."""


class NotProvidedError(RosFacadeError, NotImplementedError):
    """A ROS API the façades do not provide (yet); the message names it."""


class NotProvidedImportError(NotProvidedError, ImportError):
    """A ROS module the façades do not provide, met at an import (``import rclpy.action``)."""


def not_provided(what: str) -> str:
    """The one line that says ``what`` is not provided."""
    return f"{what} is a ROS API Skydeck does not provide (yet); what it provides is in {DOCS}"


def not_provided_attributes(module: str, names: Collection[str]) -> Callable[[str], Any]:
    """A module's ``__getattr__`` (PEP 562) for the ROS names of ``module`` that the façade does
    not have: NotProvidedError for ``names``, AttributeError for any other, as Python says it."""

    def __getattr__(name: str) -> NoReturn:
        if name in names:
            raise NotProvidedError(not_provided(f"{module}.{name}"))
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return __getattr__
