"""The system's families: service round trips, registration, start-up and memory, viewers of
the core's streams, and recording and playback."""

from __future__ import annotations

from benchmarks.report import Result, ratio_at_most
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.suite import Suite

__all__ = ["bag", "registry", "services", "startup", "viewers"]


def services(suite: Suite) -> Family:
    """service_rtt_p50, gateway_service_rtt_p50: Trigger round trips direct, through the gateway, bare FastAPI."""
    from benchmarks.services import ServiceTargets

    targets = ServiceTargets(suite.core)
    calls = suite.settings.service_calls
    trials = [
        Trial(key, label, lambda key=key: targets.measure(key, calls))  # type: ignore[misc]
        for key, label in (("skydeck", "node directly"), ("gateway", "through the gateway"), ("fastapi", "bare FastAPI"))
    ]

    def summarise(readings: Readings) -> list[Result]:
        p50 = {key: median_of(values, "p50_us") for key, values in readings.items()}
        direct = Result("service_rtt_p50", p50["skydeck"], "us", "bare FastAPI endpoint", p50["fastapi"],
                        target="<= 1.2x bare", samples=[r["p50_us"] for r in readings["skydeck"]],
                        detail={"p99_us": median_of(readings["skydeck"], "p99_us"),
                                "reference_p99_us": median_of(readings["fastapi"], "p99_us")})  # fmt: skip
        direct.met = ratio_at_most(direct, 1.2)
        gateway = Result("gateway_service_rtt_p50", p50["gateway"], "us", "direct call (service_rtt_p50)",
                         p50["skydeck"], target="<= 1.3x direct",
                         samples=[r["p50_us"] for r in readings["gateway"]],
                         detail={"p99_us": median_of(readings["gateway"], "p99_us")})  # fmt: skip
        gateway.met = ratio_at_most(gateway, 1.3)
        return [direct, gateway]

    return Family("services", trials, suite.settings.service_repetitions, summarise,
                  rows=("service_rtt_p50", "gateway_service_rtt_p50"), close=targets.close)  # fmt: skip


def registry(suite: Suite) -> Family:
    """registry_200_nodes, registry_time_per_node: sessions registering at once."""
    from benchmarks.registry import measure_registry

    small, large = 20, 200
    trials = [
        Trial("small", f"{small} nodes register", lambda: measure_registry(small)),
        Trial("large", f"{large} nodes register", lambda: measure_registry(large)),
    ]

    def summarise(readings: Readings) -> list[Result]:
        seconds = median_of(readings["large"], "seconds")
        per_node_small_ms = 1000 * median_of(readings["small"], "seconds") / small
        per_node_large_ms = 1000 * seconds / large
        return [
            Result("registry_200_nodes", seconds, "s", target="< 1 s", met=seconds < 1.0,
                   samples=[v["seconds"] for v in readings["large"]],
                   detail={"core_cpu_ms_per_node": median_of(readings["large"], "core_cpu_ms_per_node"),
                           "what": f"{large} sessions register at once, each told its topic's publisher"}),
            Result("registry_time_per_node", per_node_large_ms, "ms", reference=f"per node with {small} nodes",
                   reference_value=per_node_small_ms, target="<= 2x (linear in the graph's size)",
                   met=per_node_large_ms <= 2 * per_node_small_ms,
                   detail={"what": f"registration time per node at {large} nodes, against {small}"}),
        ]  # fmt: skip

    return Family("registry", trials, suite.settings.startup_repetitions, summarise,
                  rows=("registry_200_nodes", "registry_time_per_node"))  # fmt: skip


def startup(suite: Suite) -> Family:
    """startup, system_rss, system_pss: `skydeck launch` to every node ready, and its memory."""
    from benchmarks.startup import measure_startup

    trial = Trial("launch", "skydeck launch to every node ready", measure_startup)

    def summarise(readings: Readings) -> list[Result]:
        values = readings["launch"]
        how = values[0]["how"]
        detail = {"how": how, "processes": values[0]["processes"], "stop_s": median_of(values, "stop_s")}
        if "launch_error" in values[0]:
            detail["launch_error"] = values[0]["launch_error"]
        startup = median_of(values, "ready_s")
        rss = median_of(values, "rss_mb")
        return [
            Result("startup", startup, "s", target="< 3 s", met=startup < 3.0,
                   samples=[v["ready_s"] for v in values], detail=detail),
            Result("system_rss", rss, "MiB", target="< 400 MiB", met=rss < 400.0,
                   samples=[v["rss_mb"] for v in values],
                   detail={"what": "RSS summed over every process of the launch (shared pages counted in each)"}),
            Result("system_pss", median_of(values, "pss_mb"), "MiB", target="-",
                   samples=[v["pss_mb"] for v in values],
                   detail={"what": "PSS summed: shared pages split between the processes sharing them"}),
        ]  # fmt: skip

    return Family("startup", [trial], suite.settings.startup_repetitions, summarise,
                  rows=("startup", "system_rss", "system_pss"))  # fmt: skip


def viewers(suite: Suite) -> Family:
    """The viewers rows: 100 pose and 20 image viewers of the core, stalled readers, encodings."""
    from benchmarks.viewers import encoding_costs, run_classroom
    from benchmarks.viewers_worker import JPEG

    s = suite.settings
    trials = [
        Trial("classroom", "100 pose + 20 raw image viewers", lambda: run_classroom(suite.core, duration_s=s.viewers_s, pose=100, image=20)),
        Trial("stalled", "the same with 5 stalled readers", lambda: run_classroom(suite.core, duration_s=s.viewers_s, pose=100, image=20, stalled=5)),
        Trial("jpeg", "20 JPEG viewers", lambda: run_classroom(suite.core, duration_s=s.viewers_s, pose=0, image=20, topic=JPEG)),
        Trial("encoding", "JSON and msgpack per message", encoding_costs),
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        room, stalled, jpeg, codec = (readings[key] for key in ("classroom", "stalled", "jpeg", "encoding"))
        pose = median_of(room, "pose_delivery")
        raw_p99 = median_of(room, "image_p99_ms")
        with_stalled = median_of(stalled, "pose_delivery")
        return [
            Result("viewers_pose_delivery", pose, "of 60 Hz", target=">= 0.95 for every one of 100 viewers",
                   met=pose >= 0.95, detail={"p99_ms": median_of(room, "pose_p99_ms"), "core_cpu": median_of(room, "core_cpu")}),
            Result("image_raw_gateway_p99", raw_p99, "ms", target="< 50 ms, 640x480 at 30 Hz to 20 viewers",
                   met=raw_p99 < 50.0, detail={"delivery": median_of(room, "image_delivery"), "p50_ms": median_of(room, "image_p50_ms")}),
            Result("image_jpeg_gateway_p99", median_of(jpeg, "image_p99_ms"), "ms", target="-",
                   detail={"delivery": median_of(jpeg, "image_delivery")}),
            Result("stalled_reader_effect", with_stalled, "of 60 Hz", reference="without stalled readers",
                   reference_value=pose, target=">= 0.95x (none)", met=with_stalled >= 0.95 * pose,
                   detail={"what": "the 100 pose viewers' delivery with 5 stalled image readers on the core"}),
            Result("encoding_image_json", median_of(codec, "image_json_ms"), "ms", reference="msgpack",
                   reference_value=median_of(codec, "image_msgpack_ms"), target="-",
                   detail={"what": "make + read one 640x480 rgb8 Image (rosbridge's JSON/CBOR comparison)",
                           "json_bytes": codec[0]["image_json_bytes"], "msgpack_bytes": codec[0]["image_msgpack_bytes"]}),
            Result("encoding_pose_json", median_of(codec, "pose_json_ms") * 1000, "us", reference="msgpack",
                   reference_value=median_of(codec, "pose_msgpack_ms") * 1000, target="-"),
        ]  # fmt: skip

    return Family("viewers", trials, s.viewers_repetitions, summarise,
                  rows=("viewers_pose_delivery", "image_raw_gateway_p99", "image_jpeg_gateway_p99",
                        "stalled_reader_effect", "encoding_image_json", "encoding_pose_json"))  # fmt: skip


def bag(suite: Suite) -> Family:
    """bag_record_kept, bag_record_throughput, bag_play_timing_p99: recording and playback."""
    from benchmarks.bag import (
        measure_playback_timing,
        measure_record_throughput,
        measure_record_world,
    )

    s = suite.settings
    trials = [
        Trial("world", "bag record -a, simulator at speed max",
              lambda: measure_record_world(suite.core, window_s=s.bag_window_s)),
        Trial("throughput", "bag record, small messages as fast as published",
              lambda: measure_record_throughput(suite.core, duration_s=s.bag_window_s)),
        Trial("playback", "bag play, 100 Hz + 30 Hz to a listener", lambda: measure_playback_timing(suite.core)),
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        world, rate, timing = readings["world"], readings["throughput"], readings["playback"]
        return [
            Result("bag_record_kept", min(r["kept"] for r in world), "fraction",
                   target="1.00 (every message of every topic of the drone world at speed max)",
                   met=min(r["kept"] for r in world) >= 1.0, samples=[r["kept"] for r in world],
                   detail={"per_topic": world[0]["per_topic"], "messages_per_s": median_of(world, "rate"),
                           "topics": world[0]["topics"]}),
            Result("bag_record_throughput", median_of(rate, "rate"), "msg/s",
                   target=">= 50,000 msg/s (small messages, 2 cores)", met=median_of(rate, "rate") >= 50_000,
                   samples=[r["rate"] for r in rate],
                   detail={"kept_fraction": median_of(rate, "kept"), "publisher_rate": median_of(rate, "publisher_rate"),
                           "recorder_cpu": median_of(rate, "recorder_cpu"),
                           "recorder_us_per_msg": median_of(rate, "recorder_us_per_msg")}),
            Result("bag_play_timing_p99", median_of(timing, "p99_ms"), "ms",
                   target="< 2 ms (arrival vs recorded time)", met=median_of(timing, "p99_ms") < 2.0,
                   samples=[r["p99_ms"] for r in timing],
                   detail={"p50_ms": median_of(timing, "p50_ms"), "max_ms": median_of(timing, "max_ms"),
                           "messages": timing[0]["messages"]}),
        ]  # fmt: skip

    return Family("bag", trials, s.bag_repetitions, summarise,
                  rows=("bag_record_kept", "bag_record_throughput", "bag_play_timing_p99"))  # fmt: skip


def http_clients(suite: Suite) -> Family:
    """http_client_cpu_per_call, http_client_one_shot: Skydeck's own HTTP client against httpx."""
    from benchmarks.http_clients import ClientTargets

    targets = ClientTargets()
    calls = suite.settings.service_calls
    trials = [
        Trial(f"call:{client}", f"{client}, per call", lambda client=client: targets.per_call(client, calls))  # type: ignore[misc]
        for client in ("internal", "httpx", "httpx-sync")
    ] + [
        Trial(f"once:{client}", f"{client}, one call in a fresh process", lambda client=client: targets.one_shot(client))  # type: ignore[misc]
        for client in ("internal", "httpx")
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        cpu = {key.partition(":")[2]: median_of(values, "cpu_us") for key, values in readings.items() if key.startswith("call:")}
        once = {key.partition(":")[2]: median_of(values, "ms") for key, values in readings.items() if key.startswith("once:")}
        return [
            Result("http_client_cpu_per_call", cpu["internal"], "us CPU", "httpx.AsyncClient", cpu["httpx"],
                   target="- (the client's own CPU per kept-alive POST; why processes use their own)",
                   samples=[r["cpu_us"] for r in readings["call:internal"]],
                   detail={"httpx_sync_cpu_us": cpu["httpx-sync"],
                           "wall_us": {key.partition(":")[2]: median_of(values, "wall_us")
                                       for key, values in readings.items() if key.startswith("call:")}}),
            Result("http_client_one_shot", once["internal"], "ms", "httpx", once["httpx"],
                   target="- (spawn to exit: import, one POST; a CLI command's cost)",
                   samples=[r["ms"] for r in readings["once:internal"]]),
        ]  # fmt: skip

    return Family("http_clients", trials, suite.settings.http_client_repetitions, summarise,
                  rows=("http_client_cpu_per_call", "http_client_one_shot"), close=targets.close)  # fmt: skip
