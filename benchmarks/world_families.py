"""The world families: the simulators' real-time factor (drone and robot, node against a bare
PyBullet loop; by box count for the plot) and the AI's tours, planned and flown."""

from __future__ import annotations

from benchmarks.report import Result
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.suite import Suite

__all__ = ["flight", "mission", "robot", "rtf_by_boxes", "sim"]


def sim(suite: Suite) -> Family:
    """sim_rtf, sim_rtf_no_subscriber, sim_world_rtf: the drone world at speed max against bare PyBullet."""
    from benchmarks.sim import measure_bare, measure_node

    s = suite.settings
    trials = [
        Trial("node", "simulator node, speed max", lambda: measure_node(suite.core, boxes=8, window_s=s.sim_window_s)),
        Trial("bare", "bare PyBullet loop", lambda: measure_bare(boxes=8, steps=s.sim_bare_steps)),
    ]

    def summarise(readings: Readings) -> list[Result]:
        bare = median_of(readings["bare"], "bare_rtf")
        node = readings["node"]
        rtf = Result("sim_rtf", median_of(node, "rtf_subscribed"), "x real time", "bare PyBullet loop, same scene",
                     bare, target=">= 20x real time and >= 0.6x bare",
                     samples=[r["rtf_subscribed"] for r in node],
                     detail={"with": "a subscriber node on /drone/pose",
                             "pose_messages_per_s": median_of(node, "stream_rate")})  # fmt: skip
        rtf.met = rtf.ratio is not None and rtf.ratio >= 0.6 and (rtf.value or 0) >= 20
        alone = Result("sim_rtf_no_subscriber", median_of(node, "rtf_alone"), "x real time",
                       "bare PyBullet loop, same scene", bare, target="-",
                       samples=[r["rtf_alone"] for r in node])  # fmt: skip
        world = Result("sim_world_rtf", median_of(readings["bare"], "world_rtf"), "x real time",
                       "bare PyBullet loop, same scene", bare, target="- (World class, no node, flying)",
                       samples=[r["world_rtf"] for r in readings["bare"]])  # fmt: skip
        return [rtf, alone, world]

    return Family("sim", trials, s.sim_repetitions, summarise,
                  rows=("sim_rtf", "sim_rtf_no_subscriber", "sim_world_rtf"))  # fmt: skip


def robot(suite: Suite) -> Family:
    """The robot_* rows: the robot world at speed max against bare PyBullet with the same rays."""
    from benchmarks.sim import measure_node, measure_robot_bare

    s = suite.settings
    trials = [
        Trial("node", "robot world node, speed max",
              lambda: measure_node(suite.core, world="robot", window_s=s.sim_window_s)),
        Trial("bare", "bare PyBullet loop with the same rays", lambda: measure_robot_bare(steps=s.sim_bare_steps)),
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        bare = median_of(readings["bare"], "bare_rtf")
        node = readings["node"]
        reference = "bare PyBullet loop, same scene and rays"
        rtf = Result("robot_rtf", median_of(node, "rtf_subscribed"), "x real time", reference, bare,
                     target=">= 50x real time and >= 0.6x bare", samples=[r["rtf_subscribed"] for r in node],
                     detail={"with": "a subscriber node on /scan", "scan_messages_per_s": median_of(node, "stream_rate")})  # fmt: skip
        rtf.met = rtf.ratio is not None and rtf.ratio >= 0.6 and (rtf.value or 0) >= 50
        alone = Result("robot_rtf_no_subscriber", median_of(node, "rtf_alone"), "x real time", reference, bare,
                       target="-", samples=[r["rtf_alone"] for r in node])  # fmt: skip
        world = Result("robot_world_rtf", median_of(readings["bare"], "world_rtf"), "x real time", reference, bare,
                       target="- (RobotWorld class, no node, driving and scanning)",
                       samples=[r["world_rtf"] for r in readings["bare"]])  # fmt: skip
        per_cpu = Result("robot_rtf_per_cpu", median_of(node, "rtf_subscribed_cpu"), "x CPU time", reference,
                         median_of(readings["bare"], "bare_rtf_cpu"),
                         target="- (sim s per CPU s of the process: robot_rtf with a core to itself, on a loaded machine)",
                         samples=[r["rtf_subscribed_cpu"] for r in node])  # fmt: skip
        scan = Result("robot_scan_ms", median_of(readings["bare"], "scan_ms"), "ms a scan",
                      "one bare rayTestBatch of the same 360 rays", median_of(readings["bare"], "bare_scan_ms"),
                      target="- (360 beams, one batched ray test, 5 Hz of sim time)",
                      samples=[r["scan_ms"] for r in readings["bare"]])  # fmt: skip
        return [rtf, alone, world, per_cpu, scan]

    return Family("robot", trials, s.sim_repetitions, summarise,
                  rows=("robot_rtf", "robot_rtf_no_subscriber", "robot_world_rtf", "robot_rtf_per_cpu", "robot_scan_ms"))  # fmt: skip


def rtf_by_boxes(suite: Suite) -> Family:
    """The real-time-factor-by-box-count plot (no rows)."""
    from benchmarks.sim import measure_bare, measure_node

    s = suite.settings
    trials = []
    for boxes in s.plot_boxes:
        trials.append(Trial(f"node:{boxes}", f"simulator node, {boxes} boxes",
                            lambda b=boxes: measure_node(suite.core, boxes=b, window_s=s.sim_window_s, subscriber=False)))  # type: ignore[misc]  # fmt: skip
        trials.append(Trial(f"bare:{boxes}", f"bare loop, {boxes} boxes",
                            lambda b=boxes: measure_bare(boxes=b, steps=s.sim_bare_steps)))  # type: ignore[misc]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        suite.plot_data["rtf_by_boxes"] = {key: values[0] for key, values in readings.items()}
        return []

    return Family("plot_rtf_boxes", trials, 1, summarise)


def mission(suite: Suite) -> Family:
    """mission_tour_ratio, mission_nearest_first_ratio: planned tours against the optimum."""
    from benchmarks.mission import tours_in_worker

    worlds = suite.settings.mission_worlds
    trial = Trial("tours", f"{worlds} seeded worlds, 8 boxes", lambda: tours_in_worker(worlds=worlds, boxes=8))

    def summarise(readings: Readings) -> list[Result]:
        tours = readings["tours"][0]
        beside, home = tours["beside_last_box"], tours["home"]
        return [
            Result("mission_tour_ratio", beside["mean_ratio"], "x optimal",
                   target="1.00 on every world (planned flight, landing beside the last box)",
                   met=beside["worst_ratio"] <= 1.0 + 1e-9,
                   detail={"worst_ratio": beside["worst_ratio"], "optimal_worlds": beside["optimal_worlds"],
                           "worlds": tours["worlds"], "plan_ms_median": tours["plan_ms_median"],
                           "home_mean_ratio": home["mean_ratio"], "home_worst_ratio": home["worst_ratio"]}),
            Result("mission_nearest_first_ratio", tours["nearest_first_mean_ratio"], "x optimal",
                   target="- (the workshop's nearest-first bonus, open tour, for scale)",
                   detail={"worst_ratio": tours["nearest_first_worst_ratio"]}),
        ]  # fmt: skip

    return Family("mission", [trial], 1, summarise, rows=("mission_tour_ratio", "mission_nearest_first_ratio"))


def flight(suite: Suite) -> Family:
    """mission_flown_ratio, mission_time: missions flown in the simulator."""
    from benchmarks.mission import flights_in_worker

    seeds = tuple(range(suite.settings.mission_flights))
    trial = Trial("flights", f"{len(seeds)} missions flown, 8 boxes", lambda: flights_in_worker(seeds=seeds, boxes=8))

    def summarise(readings: Readings) -> list[Result]:
        flown = readings["flights"][0]
        per_flight = [{k: f[k] for k in ("seed", "ratio", "flight_s", "missed_poses")} for f in flown["flights"]]
        return [
            Result("mission_flown_ratio", flown["mean_ratio"], "x optimal",
                   target="<= 1.05 (ground track, take-off to touchdown)",
                   met=flown["worst_ratio"] <= 1.05 and flown["completed"] == len(seeds),
                   detail={"worst_ratio": flown["worst_ratio"], "completed": flown["completed"],
                           "flights": per_flight}),
            Result("mission_time", flown["flight_s_median"], "s (sim)",
                   reference="optimal track at top speed", reference_value=flown["least_flight_s_median"],
                   target="- (take-off to touchdown)"),
        ]  # fmt: skip

    return Family("flight", [trial], 1, summarise, rows=("mission_flown_ratio", "mission_time"))


def grading(suite: Suite) -> Family:
    """grade_run_s, grade_step_ms, grade_sim_rate: ``skydeck grade`` of one behaviour, one seed
    (:mod:`benchmarks.grading`)."""
    from benchmarks.grading import measure_grading

    trial = Trial("grade", "skydeck grade wall_follower.yaml wall_follower, one seed", measure_grading)

    def summarise(readings: Readings) -> list[Result]:
        got = readings["grade"]
        return [
            Result("grade_run_s", median_of(got, "wall_s"), "s", target="< 30 s (one behaviour, one seed)",
                   met=median_of(got, "wall_s") < 30.0, samples=[r["wall_s"] for r in got],
                   detail={"sim_time_s": got[0]["sim_time_s"], "cpu_s_while_stepping": got[0]["cpu_s"]}),
            Result("grade_step_ms", median_of(got, "step_ms"), "ms a step", "CPU ms a step, every process",
                   median_of(got, "cpu_ms_per_step"), target="- (1/30 sim s a step, in lockstep)",
                   samples=[r["step_ms"] for r in got]),
            Result("grade_sim_rate", median_of(got, "sim_rate"), "x real time", target="- (while stepping)",
                   samples=[r["sim_rate"] for r in got]),
        ]  # fmt: skip

    return Family("grading", [trial], suite.settings.grading_repetitions, summarise,
                  rows=("grade_run_s", "grade_step_ms", "grade_sim_rate"))  # fmt: skip
