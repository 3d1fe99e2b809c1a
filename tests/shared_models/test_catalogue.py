"""The message catalogue loads every message package, so no type is missing from the lookup."""

from __future__ import annotations

import importlib
import pkgutil

import shared_models
from shared_models._message import Message, ServiceType
from shared_models.catalogue import MESSAGE_PACKAGES


def test_every_module_that_defines_types_is_in_the_catalogue() -> None:
    """A package's (rosapi_msgs') types are defined in its modules, so they count as its."""
    defining = set()
    for info in pkgutil.iter_modules(shared_models.__path__):
        module = importlib.import_module(f"shared_models.{info.name}")
        for value in vars(module).values():
            if (
                isinstance(value, type)
                and issubclass(value, Message | ServiceType)
                and (value.__module__ == module.__name__ or value.__module__.startswith(module.__name__ + "."))
                and value.__dict__.get("__ros_type__")
            ):
                defining.add(info.name)
    assert defining == set(MESSAGE_PACKAGES)


def test_lookup_knows_the_types_of_every_package() -> None:
    names = shared_models.interface_names()
    for package in ("geometry_msgs", "sensor_msgs", "visualization_msgs", "tf2_msgs", "neato2_interfaces"):
        assert any(name.startswith(package + "/") for name in names), package
