"""The topic families: throughput and latency (Skydeck, a bare websockets pair, zenoh), by
message size for the plot, through the rosbridge endpoint, and fan-out to 100 nodes."""

from __future__ import annotations

from typing import Any

from benchmarks.report import Result, ratio_at_most
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.suite import Suite
from benchmarks.topics import CoreHolder, run_topic_pair

BARE_WS = "bare websockets pair"
ROSBRIDGE_MSGS_S = 5_000.0  # what rosbridge users report; the issue asks for 10x that

__all__ = ["fanout", "latency", "ros2", "rosbridge", "throughput", "throughput_by_size"]


def _topic_trial(suite: Suite, transport: str, mode: str, **options: Any) -> Trial:
    s = suite.settings

    def run() -> dict[str, Any]:
        pair = run_topic_pair(
            transport,
            mode=mode,
            duration_s=s.throughput_s if mode == "throughput" else s.latency_s,
            rate_hz=s.latency_rate_hz,
            core=suite.core,
            **options,
        )
        sent = pair.publisher["sent"]
        return {
            **pair.subscriber,
            "publisher_rate": pair.publisher["rate"],
            "publisher_cpu": pair.publisher["cpu_s"] / pair.publisher["wall_s"],
            "delivered": pair.subscriber["received"] / sent if sent else 0.0,
        }

    return Trial(transport, f"{transport} {mode}", run)


def throughput(suite: Suite) -> Family:
    """topic_throughput, zenoh_throughput: messages a second from one publisher to one subscriber."""
    trials = [_topic_trial(suite, t, "throughput") for t in ("skydeck", "websockets", "zenoh")]

    def summarise(readings: Readings) -> list[Result]:
        rate = {key: median_of(values, "rate") for key, values in readings.items()}
        sky = Result(
            "topic_throughput", rate["skydeck"], "msg/s", BARE_WS, rate["websockets"],
            target=f">= 1.0x bare and >= {10 * ROSBRIDGE_MSGS_S:,.0f} msg/s (10x rosbridge)",
            samples=[r["rate"] for r in readings["skydeck"]],
            detail={
                "publisher_rate": median_of(readings["skydeck"], "publisher_rate"),
                "delivered_fraction": median_of(readings["skydeck"], "delivered"),
                "publisher_cpu": median_of(readings["skydeck"], "publisher_cpu"),
                "reference_samples": [r["rate"] for r in readings["websockets"]],
            },
        )  # fmt: skip
        sky.met = sky.ratio is not None and sky.ratio >= 1.0 and rate["skydeck"] >= 10 * ROSBRIDGE_MSGS_S
        zenoh = Result(
            "zenoh_throughput", rate["zenoh"], "msg/s", BARE_WS, rate["websockets"],
            target="peer, for comparison", samples=[r["rate"] for r in readings["zenoh"]],
        )  # fmt: skip
        return [sky, zenoh]

    return Family("topic_throughput", trials, suite.settings.topic_repetitions, summarise,
                  rows=("topic_throughput", "zenoh_throughput"))  # fmt: skip


def latency(suite: Suite) -> Family:
    """topic_latency_p50/p99, zenoh_latency_p50/p99: one-way latency at a fixed rate."""
    trials = [_topic_trial(suite, t, "latency") for t in ("skydeck", "websockets", "zenoh")]

    def summarise(readings: Readings) -> list[Result]:
        p50 = {key: median_of(values, "p50_us") for key, values in readings.items()}
        p99 = {key: median_of(values, "p99_us") for key, values in readings.items()}
        suite.plot_data["latency_samples_us"] = {
            key: [x for r in values for x in r["samples_us"]] for key, values in readings.items()
        }
        rate = f"{suite.settings.latency_rate_hz:,.0f} msg/s"
        rows = [
            Result("topic_latency_p50", p50["skydeck"], "us", BARE_WS, p50["websockets"],
                   target="<= 1.3x bare", samples=[r["p50_us"] for r in readings["skydeck"]],
                   detail={"rate": rate, "mean_us": median_of(readings["skydeck"], "mean_us")}),
            Result("topic_latency_p99", p99["skydeck"], "us", BARE_WS, p99["websockets"],
                   target="< 2,000 us", met=p99["skydeck"] < 2000.0,
                   samples=[r["p99_us"] for r in readings["skydeck"]],
                   detail={"max_us": median_of(readings["skydeck"], "max_us")}),
            Result("zenoh_latency_p50", p50["zenoh"], "us", BARE_WS, p50["websockets"],
                   target="peer, for comparison", samples=[r["p50_us"] for r in readings["zenoh"]]),
            Result("zenoh_latency_p99", p99["zenoh"], "us", BARE_WS, p99["websockets"],
                   target="peer, for comparison", samples=[r["p99_us"] for r in readings["zenoh"]]),
        ]  # fmt: skip
        rows[0].met = ratio_at_most(rows[0], 1.3)
        return rows

    return Family("topic_latency", trials, suite.settings.topic_repetitions, summarise,
                  rows=("topic_latency_p50", "topic_latency_p99", "zenoh_latency_p50", "zenoh_latency_p99"))  # fmt: skip


def throughput_by_size(suite: Suite) -> Family:
    """The throughput-by-message-size plot (no rows)."""
    trials = [
        Trial(f"{transport}:{size}", f"{transport} {size} B", _topic_trial_sized(suite, transport, size))
        for size in suite.settings.plot_sizes
        for transport in ("skydeck", "websockets", "zenoh")
    ]

    def summarise(readings: Readings) -> list[Result]:
        suite.plot_data["throughput_by_size"] = {key: values[0]["rate"] for key, values in readings.items()}
        return []

    return Family("plot_throughput_size", trials, 1, summarise)


def _topic_trial_sized(suite: Suite, transport: str, size: int) -> Any:
    def run() -> dict[str, Any]:
        pair = run_topic_pair(transport, mode="throughput", duration_s=suite.settings.plot_throughput_s,
                              core=suite.core, size_bytes=size)  # fmt: skip
        return pair.subscriber

    return run


def rosbridge(suite: Suite) -> Family:
    """rosbridge_throughput, rosbridge_rtt_p50: the rosbridge endpoint against the core's native stream."""
    from benchmarks.bridges import ROSBRIDGE_RTT_MS, run_bridge_rtt, run_bridge_throughput

    core = CoreHolder(rosbridge=True)
    s = suite.settings
    trials = [
        Trial(f"{mode}:{via}", f"{via} {mode}", lambda via=via, mode=mode: (  # type: ignore[misc]
            run_bridge_throughput(via, core, duration_s=s.throughput_s) if mode == "throughput"
            else run_bridge_rtt(via, core, duration_s=s.latency_s, rate_hz=s.latency_rate_hz)))
        for mode in ("throughput", "rtt")
        for via in ("rosbridge", "native")
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        rate = {via: median_of(readings[f"throughput:{via}"], "rate") for via in ("rosbridge", "native")}
        rtt = {via: median_of(readings[f"rtt:{via}"], "p50_us") for via in ("rosbridge", "native")}
        throughput = Result(
            "rosbridge_throughput", rate["rosbridge"], "msg/s", "the core's native stream", rate["native"],
            target=f">= 0.7x native and >= {10 * ROSBRIDGE_MSGS_S:,.0f} msg/s (10x rosbridge_suite's "
                   f"{ROSBRIDGE_MSGS_S:,.0f})",
            samples=[r["rate"] for r in readings["throughput:rosbridge"]],
            detail={"delivered_fraction": median_of(readings["throughput:rosbridge"], "delivered"),
                    "reference_samples": [r["rate"] for r in readings["throughput:native"]]},
        )
        throughput.met = (
            throughput.ratio is not None and throughput.ratio >= 0.7 and rate["rosbridge"] >= 10 * ROSBRIDGE_MSGS_S
        )
        round_trip = Result(
            "rosbridge_rtt_p50", rtt["rosbridge"] / 1000, "ms", "the core's native stream", rtt["native"] / 1000,
            target=f"<= 1/0.7 x native and <= {ROSBRIDGE_RTT_MS / 10:g} ms (10x better than rosbridge_suite's "
                   f"{ROSBRIDGE_RTT_MS:g} ms)",
            samples=[r["p50_us"] / 1000 for r in readings["rtt:rosbridge"]],
            detail={"p99_ms": median_of(readings["rtt:rosbridge"], "p99_us") / 1000,
                    "rate": f"{s.latency_rate_hz:,.0f} msg/s",
                    "path": "client -> core -> echo node -> core -> client"},
        )
        round_trip.met = (
            round_trip.ratio is not None
            and round_trip.ratio <= 1 / 0.7
            and rtt["rosbridge"] / 1000 <= ROSBRIDGE_RTT_MS / 10
        )
        return [throughput, round_trip]

    return Family("rosbridge", trials, s.topic_repetitions, summarise,
                  rows=("rosbridge_throughput", "rosbridge_rtt_p50"), close=core.close)  # fmt: skip


def fanout(suite: Suite) -> Family:
    """fanout_100, fanout_100_publisher_cpu: one publisher to 100 subscriber nodes at 30 Hz."""
    from benchmarks.fanout import run_fanout

    trial = Trial("fanout", "100 subscriber nodes at 30 Hz",
                  lambda: run_fanout(suite.core, duration_s=suite.settings.fanout_s))  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        values = readings["fanout"]
        delivered = median_of(values, "delivered")
        return [
            Result("fanout_100", delivered, "fraction", target="1.00 (every message to every subscriber)",
                   met=min(v["delivered"] for v in values) >= 1.0, samples=[v["delivered"] for v in values],
                   detail={"messages_per_repetition": values[0]["published"],
                           "latency_p50_us": median_of(values, "latency_p50_us"),
                           "latency_p99_us": median_of(values, "latency_p99_us")}),
            Result("fanout_100_publisher_cpu", 100 * median_of(values, "publisher_cpu"), "% of a core",
                   target="-", samples=[100 * v["publisher_cpu"] for v in values]),
        ]  # fmt: skip

    return Family("fanout", [trial], suite.settings.fanout_repetitions, summarise,
                  rows=("fanout_100", "fanout_100_publisher_cpu"))  # fmt: skip


def ros2(suite: Suite) -> list[Family]:
    """The ROS 2 bridge's rows (benchmarks/ros2.py), only where the ros2 extra is installed."""
    from services.protocols.ros2.extra import missing_extra

    if missing_extra() is not None:
        return []
    from benchmarks.ros2 import ros2_family

    return [ros2_family(suite.settings.topic_repetitions, suite.settings.throughput_s * 2)]
