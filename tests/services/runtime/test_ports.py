"""Port probing shared by the launch supervisor, the benchmark and the tests."""

from __future__ import annotations

import socket

import pytest

from services.runtime.ports import free_port_block, port_is_free

pytestmark = pytest.mark.timeout(10)


def test_a_listening_port_is_not_free_and_a_closed_one_is() -> None:
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        port = listener.getsockname()[1]
        assert not port_is_free(port)
    assert port_is_free(port)


def test_a_block_is_free_and_below_the_outgoing_connection_range() -> None:
    base = free_port_block(5)
    assert base >= 20000 and base + 4 < 32000
    assert all(port_is_free(base + offset) for offset in range(5))
