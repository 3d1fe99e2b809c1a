"""The SDK's lazy exports: every name resolves to the object its module defines, and the light
parts load without FastAPI, uvicorn or httpx (what keeps ``skydeck launch`` and the CLI small)."""

from __future__ import annotations

import importlib
import subprocess
import sys
import types

import pytest

import services.runtime

pytestmark = pytest.mark.timeout(60)


@pytest.mark.parametrize("name", services.runtime.__all__)
def test_every_export_is_the_object_of_its_module(name: str) -> None:
    home = importlib.import_module(services.runtime._HOMES[name])  # also sets submodule attributes
    exported = getattr(services.runtime, name)
    assert not isinstance(exported, types.ModuleType), f"{name} is shadowed by a submodule of the same name"
    assert exported is getattr(home, name)


def test_unknown_name_is_an_attribute_error() -> None:
    with pytest.raises(AttributeError, match="no attribute 'Nope'"):
        services.runtime.Nope  # noqa: B018


@pytest.mark.parametrize(
    "module",
    ["services.cli.main", "services.launch", "services.runtime.http_client", "services.runtime.settings"],
)
def test_light_modules_do_not_load_the_web_stack(module: str) -> None:
    # shared_models itself is light (names, errors); its message types (_message) are not.
    heavy = ("fastapi", "uvicorn", "httpx", "shared_models._message")
    code = f"import sys, {module}; print(','.join(m for m in {heavy!r} if m in sys.modules))"
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert loaded == "", f"importing {module} loads {loaded}"
