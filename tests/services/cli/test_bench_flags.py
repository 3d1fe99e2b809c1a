"""`skydeck bench`'s plot flags, as the CLI hands them to the benchmark (unit: the run itself is
replaced; tests/benchmarks runs it for real)."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

import benchmarks
from services.cli.bench import _DEFAULT_PLOTS
from services.cli.main import main


@pytest.fixture
def asked(monkeypatch: pytest.MonkeyPatch) -> dict[str, Any]:
    """What `skydeck bench` asked run_bench for, instead of running it."""
    seen: dict[str, Any] = {}

    def run_bench(**options: Any) -> SimpleNamespace:
        seen.update(options)
        return SimpleNamespace(table="(table)", plots=[], errors=[])

    monkeypatch.setattr(benchmarks, "run_bench", run_bench)
    return seen


def test_plots_go_where_asked_and_no_plots_wins(asked: dict[str, Any], tmp_path: Path) -> None:
    assert main(["bench", "--quick", "--plots", str(tmp_path)]) == 0
    assert asked["plots"] == tmp_path and asked["quick"] is True
    assert main(["bench", "--quick", "--plots", str(tmp_path), "--no-plots"]) == 0
    assert asked["plots"] is None
    assert main(["bench", "--no-plots", "--only", "service_rtt_p50"]) == 0
    assert asked["plots"] is None and asked["only"] == {"service_rtt_p50"}


def test_a_full_run_plots_into_the_docs_and_a_quick_one_nowhere(asked: dict[str, Any]) -> None:
    assert main(["bench", "--quick"]) == 0
    assert asked["plots"] is None
    assert main(["bench"]) == 0
    assert asked["plots"] == (_DEFAULT_PLOTS if _DEFAULT_PLOTS.is_dir() else None)


def test_without_the_checkouts_benchmarks_the_verb_says_so_in_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """An installation without benchmarks/ (the Docker image): one line, exit 1, no traceback."""
    find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *rest: None if name == "benchmarks" else find_spec(name, *rest))
    assert main(["bench", "--quick"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("skydeck: error: skydeck bench runs the benchmark suite of a Skydeck checkout")
    assert err.count("\n") == 1
