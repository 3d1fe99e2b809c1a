"""Where others reach a server: the address it listens on, or the machine's name for 'any'."""

from __future__ import annotations

import socket

import pytest

from services.runtime.settings import reachable_host


@pytest.mark.parametrize("host", ["0.0.0.0", "::", ""])
def test_listening_everywhere_is_reached_by_the_machine_name(host: str) -> None:
    assert reachable_host(host) == socket.gethostname()


@pytest.mark.parametrize("host", ["127.0.0.1", "core", "10.0.0.5"])
def test_a_real_address_is_kept(host: str) -> None:
    assert reachable_host(host) == host
