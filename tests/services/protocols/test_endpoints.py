"""The table of endpoints is the one place an endpoint is named: its rows give the flags, the
settings, the variables and the plugins, and the launch moves each port with the base port."""

from __future__ import annotations

import argparse

import pytest

from services.cli.run import add_endpoint_flags
from services.launch.settings import LaunchSettings
from services.protocols.endpoints import DEFAULT_BASE_PORT, ENDPOINTS, endpoint_named, load_plugin
from services.protocols.settings import CoreProcessSettings

pytestmark = pytest.mark.timeout(30)


@pytest.mark.parametrize("endpoint", ENDPOINTS, ids=lambda e: e.name)
def test_a_row_names_its_flag_setting_variable_and_plugin(endpoint, monkeypatch: pytest.MonkeyPatch) -> None:  # type: ignore[no-untyped-def]
    assert endpoint.flag == f"--{endpoint.name}-port" and endpoint.setting == f"{endpoint.name}_port"
    assert endpoint.env_var == f"SKYDECK_{endpoint.name.upper()}_PORT"
    assert load_plugin(endpoint).name == endpoint.name  # the package's plugin is the row's
    assert endpoint_named(endpoint.name) is endpoint
    monkeypatch.delenv(endpoint.env_var, raising=False)
    assert CoreProcessSettings().endpoint_port(endpoint) == endpoint.default_port
    assert CoreProcessSettings(**{endpoint.setting: 0}).endpoint_port(endpoint) == 0
    monkeypatch.setenv(endpoint.env_var, "12345")
    assert CoreProcessSettings().endpoint_port(endpoint) == 12345
    assert LaunchSettings().endpoint_ports()[endpoint.name] == 12345
    parser = argparse.ArgumentParser()
    add_endpoint_flags(parser)
    assert getattr(parser.parse_args([endpoint.flag, "7"]), endpoint.setting) == 7
    assert endpoint.port_at(DEFAULT_BASE_PORT) == endpoint.default_port
    assert endpoint.port_at(DEFAULT_BASE_PORT + 30) == endpoint.default_port + 30


def test_the_tools_own_ports_and_an_unknown_name() -> None:
    assert {e.name: e.default_port for e in ENDPOINTS} == {"rosbridge": 9090, "foxglove": 8765}
    with pytest.raises(KeyError, match="the endpoints are rosbridge, foxglove"):
        endpoint_named("mqtt")
