"""`skydeck bench` produces its table and JSON: structure only, never timings (shared machines)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from benchmarks.mission import (
    GroundTrack,
    brute_force_length,
    nearest_first_length,
    optimal_flight_m,
)
from benchmarks.report import Result, format_table
from benchmarks.runner import Family, Progress, Trial, run_families
from benchmarks.sink import Sink, percentile

REQUIRED_KEYS = {"name", "value", "unit", "reference", "reference_value", "ratio"}


def _bench(tmp_path: Path, *args: str, timeout_s: float) -> tuple[subprocess.CompletedProcess[str], dict]:
    out = tmp_path / "bench.json"
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "bench", "--quick", "--out", str(out), *args],
        capture_output=True,
        text=True,
        timeout=timeout_s,
        cwd=tmp_path,  # no docs/img here: nothing may be written outside --out
    )
    assert done.returncode == 0, (done.stdout[-4000:], done.stderr[-1500:])  # the table says which row errored
    return done, json.loads(out.read_text())


@pytest.mark.timeout(180)  # a hang guard, sized for a loaded machine
def test_quick_run_of_two_families_writes_the_json_and_the_table(tmp_path: Path) -> None:
    done, document = _bench(tmp_path, "--only", "mission,service_rtt_p50", timeout_s=170)
    rows = {row["name"]: row for row in document["results"]}
    assert {"mission_tour_ratio", "service_rtt_p50", "gateway_service_rtt_p50"} <= set(rows)
    for row in document["results"]:
        assert set(row) >= REQUIRED_KEYS
        assert row["error"] is None
        assert isinstance(row["value"], float)
    direct = rows["service_rtt_p50"]
    assert direct["reference"] == "bare FastAPI endpoint"
    assert direct["ratio"] == pytest.approx(direct["value"] / direct["reference_value"])
    assert rows["mission_tour_ratio"]["reference"] is None and rows["mission_tour_ratio"]["ratio"] is None
    assert {"cpu", "logical_cpus", "python", "packages"} <= set(document["machine"])
    assert document["run"]["quick"] is True
    assert "service_rtt_p50" in done.stdout and "mission_tour_ratio" in done.stdout
    assert "[" in done.stderr  # the progress bar
    assert list(tmp_path.iterdir()) == [tmp_path / "bench.json"]


@pytest.mark.slow
@pytest.mark.timeout(300)
def test_plots_are_written_where_asked(tmp_path: Path) -> None:
    plots = tmp_path / "plots"
    done, document = _bench(tmp_path, "--only", "topic_latency_p50", "--plots", str(plots), timeout_s=280)
    assert document["run"]["plots"] == [str(plots / "bench_latency.png")]
    assert (plots / "bench_latency.png").stat().st_size > 0 and f"plot written to {plots}" in done.stderr


def test_unknown_only_name_is_a_one_line_error(tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "bench", "--quick", "--only", "warp_speed"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.returncode == 1
    assert done.stderr.startswith("skydeck: error: --only: unknown warp_speed; known:")


@pytest.mark.slow
@pytest.mark.timeout(660)
def test_whole_quick_run_has_every_row_of_the_issue(tmp_path: Path) -> None:
    _, document = _bench(tmp_path, timeout_s=650)
    names = {row["name"] for row in document["results"]}
    assert {
        "topic_throughput", "topic_latency_p50", "topic_latency_p99", "fanout_100", "service_rtt_p50",
        "gateway_service_rtt_p50", "sim_rtf", "mission_tour_ratio", "mission_flown_ratio", "mission_time",
        "startup", "zenoh_throughput", "zenoh_latency_p50", "robot_rtf", "robot_world_rtf", "robot_scan_ms",
        "robot_rtf_per_cpu", "grade_run_s",
    } <= names  # fmt: skip


# -- the pieces, without processes ------------------------------------------------------------


def test_runner_alternates_order_and_a_failing_family_becomes_error_rows() -> None:
    from benchmarks.processes import BenchError

    order: list[str] = []

    def trial(key: str) -> Trial:
        return Trial(key, key, lambda: order.append(key) or {"v": float(len(order))})

    def broken() -> dict[str, float]:
        raise BenchError("worker never got ready")

    good = Family("good", [trial("a"), trial("b")], 3, lambda r: [Result("good_row", r["a"][0]["v"], "x")])
    bad = Family("bad", [Trial("x", "x", broken)], 2, lambda r: [], rows=("bad_row",))
    with open("/dev/null", "w") as sink:
        results = run_families([good, bad], Progress(8, stream=sink))
    assert order == ["a", "b", "b", "a", "a", "b"]
    assert [r.name for r in results] == ["good_row", "bad_row"]
    assert results[1].error == "worker never got ready" and results[1].value is None
    assert "ERROR" in format_table(results)


def test_result_json_has_ratio_and_no_nan() -> None:
    row = Result("x", 2.0, "us", "ref", 4.0, detail={"p": float("nan")}).as_json()
    assert list(row)[:6] == ["name", "value", "unit", "reference", "reference_value", "ratio"]
    assert row["ratio"] == 0.5 and row["detail"]["p"] is None


def test_sink_counts_after_warmup_and_percentiles() -> None:
    sink = Sink("throughput", warmup_s=0.0)
    for _ in range(5):
        sink.arrive()
    summary = sink.summary()
    assert summary["received"] == summary["counted"] == 5
    assert percentile([1.0, 2.0, 3.0, 4.0, 5.0], 0.5) == 3.0


def test_brute_force_finds_the_tour_nearest_first_misses() -> None:
    points = [(5.0, 0.0), (-1.0, 0.0), (6.0, 0.0), (-7.0, 0.0)]
    assert brute_force_length((0.0, 0.0), points) == pytest.approx(19.0)  # 0 -> 5 -> 6 -> -1 -> -7
    assert nearest_first_length((0.0, 0.0), points) == pytest.approx(21.0)  # 0 -> -1 -> 5 -> 6 -> -7


def test_the_optimum_for_each_landing_policy() -> None:
    from services.ai.landing import CLEARANCE_M

    points = [(5.0, 0.0), (-1.0, 0.0), (6.0, 0.0), (-7.0, 0.0)]
    home = [abs(x) for x, _ in points]
    assert brute_force_length((0.0, 0.0), points, home) == pytest.approx(26.0)  # closed: 2 * (6 + 7)
    assert optimal_flight_m((0.0, 0.0), points, "home") == pytest.approx(26.0)
    assert optimal_flight_m((0.0, 0.0), points, "beside_last_box") == pytest.approx(19.0 + CLEARANCE_M)


def _pose(seq: int, t: float, x: float, y: float, z: float) -> dict:
    stamp = {"sec": int(t), "nanosec": int(round((t - int(t)) * 1e9))}
    return {"header": {"seq": seq, "stamp": stamp}, "pose": {"position": {"x": x, "y": y, "z": z}}}


def test_ground_track_runs_from_take_off_to_touchdown() -> None:
    track = GroundTrack([(3.0, 4.0)])
    poses = [
        (0.0, 0.0, 0.05),  # on the ground: not counted
        (0.0, 0.0, 1.0),  # take-off at t = 1
        (3.0, 4.0, 3.0),  # 5 m
        (3.0, 8.0, 3.0),  # 4 m
        (3.0, 8.0, 0.05),  # touchdown at t = 4
        (9.0, 8.0, 0.05),  # dragged on the ground afterwards: not counted
    ]
    for seq, (x, y, z) in enumerate(poses):
        track.add(_pose(seq + 1, float(seq), x, y, z))
        assert track.landed == (seq >= 4)
    assert track.track_m == pytest.approx(9.0) and track.flight_s == pytest.approx(3.0)
    assert track.closest == [0.0] and track.missed == 0
    track.add(_pose(10, 6.0, 9.0, 8.0, 0.05))
    assert track.missed == 3


@pytest.mark.slow
@pytest.mark.timeout(150)
def test_a_short_soak_samples_every_process_under_load(tmp_path: Path) -> None:
    """`skydeck bench --soak MINUTES`: a row per process of the launch, and the load it ran under."""
    out = tmp_path / "soak.json"
    done = subprocess.run(
        [sys.executable, "-m", "services.cli", "bench", "--soak", "0.3", "--out", str(out)],
        capture_output=True, text=True, timeout=140, cwd=tmp_path,
    )  # fmt: skip
    assert "Traceback" not in done.stderr, done.stderr[-2000:]
    rows = {row["name"]: row for row in json.loads(out.read_text())["results"]}
    assert {"soak_rss_sim", "soak_rss_control", "soak_rss_ai", "soak_rss_skydeck_core"} <= set(rows)
    slope = rows.pop("soak_rss_slope")
    assert slope["unit"] == "MiB/min" and "soak_rss" + slope["detail"]["process"].replace("/", "_") in rows
    assert all(row["value"] > 10 and row["reference"] == "after warm-up" for row in rows.values())
    counters = json.loads(out.read_text())["run"]["counters"]
    assert counters["frames"] > 1000 and counters["stalled_readers"] >= 1
