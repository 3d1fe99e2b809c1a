"""One error tree: every exception the project defines descends from SkydeckError, and the
edges map each to an HTTP status and a close code from the class itself."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import pytest

import services
import shared_models
import sim_server
from shared_models.errors import SkydeckError

pytestmark = pytest.mark.timeout(60)


def _project_modules() -> list[str]:
    names = []
    for package in (shared_models, services, sim_server):
        for info in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
            if not info.name.endswith("__main__"):
                names.append(info.name)
    return names


def _exception_classes() -> list[type[BaseException]]:
    found = []
    for name in _project_modules():
        module = importlib.import_module(name)
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if issubclass(cls, BaseException) and cls.__module__ == name:
                found.append(cls)
    return found


def test_every_project_exception_descends_from_skydeck_error() -> None:
    classes = _exception_classes()
    assert len(classes) >= 15, [c.__name__ for c in classes]  # the walk really found them
    outside = [f"{c.__module__}.{c.__qualname__}" for c in classes if not issubclass(c, SkydeckError)]
    assert outside == []


def test_errors_keep_the_builtin_class_callers_expect() -> None:
    from shared_models import InvalidNameError, UnknownInterfaceError
    from sim_server.checks import InvalidCommand

    assert issubclass(InvalidNameError, ValueError) and issubclass(InvalidCommand, ValueError)
    assert issubclass(UnknownInterfaceError, LookupError)


def test_edges_read_status_and_close_code_from_the_error() -> None:
    from services.runtime.edge.frames import FrameRejected
    from services.runtime.errors import ServiceTimeoutError, ServiceUnavailableError
    from shared_models import InvalidNameError

    assert (InvalidNameError("x y", "spaces").http_status, InvalidNameError("x y", "spaces").close_code) == (404, 1008)
    assert FrameRejected(1007, "bad").close_code == 1007
    assert ServiceUnavailableError("/x", "down").http_status == 503
    assert ServiceTimeoutError("/x", "slow").http_status == 504
