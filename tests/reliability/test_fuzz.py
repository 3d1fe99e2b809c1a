"""Schemathesis against the running workshop system: the core's aggregated OpenAPI (its own API
and, through the gateway, every node's services and topics) and each node's own OpenAPI.
Positive and negative cases for every operation, bounded; no 5xx, and every response matches
its schema (status code, content type, body).
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
import schemathesis
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis.errors import Unsatisfiable

from services.runtime.parameter_service import PARAMETER_SERVICES
from tests.reliability.conftest import Workshop

pytestmark = [pytest.mark.e2e, pytest.mark.timeout(120)]

EXAMPLES_PER_OPERATION = 30
MODES = (schemathesis.GenerationMode.POSITIVE, schemathesis.GenerationMode.NEGATIVE)


def _fuzz(base_url: str, *, skip: Callable[[str, str], bool] = lambda method, path: False) -> tuple[int, int]:
    """Fuzz every operation of the OpenAPI at ``base_url`` but those ``skip`` names by method
    (``PUT``) and path; (operations, cases sent)."""
    schema = schemathesis.openapi.from_url(base_url + "/openapi.json", timeout=10)
    operations = [
        op for op in (result.ok() for result in schema.get_all_operations()) if not skip(op.method.upper(), op.path)
    ]
    sent = 0
    for operation in operations:
        for mode in MODES:

            @given(case=operation.as_strategy(generation_mode=mode))
            @settings(
                max_examples=EXAMPLES_PER_OPERATION,
                deadline=None,
                database=None,
                phases=[Phase.explicit, Phase.generate],  # no shrinking: a failure is reported as found
                suppress_health_check=list(HealthCheck),
            )
            def run(case: schemathesis.Case) -> None:
                nonlocal sent
                sent += 1
                case.call_and_validate(base_url=base_url, timeout=15)

            try:
                run()
            except Unsatisfiable:
                if mode is not schemathesis.GenerationMode.NEGATIVE:
                    raise
                # Nothing to get wrong (no parameters, no body): no negative case exists.
    return len(operations), sent


def _another_nodes_parameter_service(path: str) -> bool:
    """Every node's six parameter services are the same code, fuzzed on each node below: through
    the core, those of one node (control) are enough, and keep the run within its time."""
    node, _, verb = path.rpartition("/")
    return verb in PARAMETER_SERVICES and node != "/control"


def _setting_a_ros1_parameter(method: str, path: str) -> bool:
    """PUT /api/rosparam/...: its schema takes any JSON value (``value: Any``), and the server
    refuses null (as rosmaster does) with its own one line, so the fuzzer's schema-valid
    ``{"value": null}`` is a false "schema-valid request rejected" (ST202).
    tests/services/core/test_parameter_server.py covers its refusals; GET and DELETE are fuzzed."""
    return method == "PUT" and path.startswith("/api/rosparam")


def _skipped_through_the_core(method: str, path: str) -> bool:
    return _another_nodes_parameter_service(path) or _setting_a_ros1_parameter(method, path)


def test_core_openapi_fuzzed_no_5xx_and_responses_conform(workshop: Workshop) -> None:
    operations, sent = _fuzz(workshop.core_url, skip=_skipped_through_the_core)
    paths = set(schemathesis.openapi.from_url(workshop.core_url + "/openapi.json").raw_schema["paths"])
    # The aggregated page covers the core's API and every node's services (through the gateway).
    assert {"/api/graph", "/control/fly", "/simulator/reset", "/ai/start", "/drone/pose", "/control/set_parameters"} <= paths
    print(f"fuzz core: {operations} operations, {sent} cases")
    for node in workshop.node_urls:
        assert workshop.node_serves(node), node


@pytest.mark.parametrize("node", ["/sim", "/perception", "/control", "/ai"])
def test_node_openapi_fuzzed_no_5xx_and_responses_conform(workshop: Workshop, node: str) -> None:
    operations, sent = _fuzz(workshop.node_urls[node])
    print(f"fuzz {node}: {operations} operations, {sent} cases")
    assert operations >= 2
    assert workshop.node_serves(node)
