"""The simulator's real camera: frames a second delivered to a reader of
``/simulator/camera/image_raw`` (msgpack, straight from the simulator node) at 30 Hz asked, and
the simulator's pace meanwhile (sim seconds per wall second at ``--speed 1``: 1.0 is keeping
up). The node is the real one, ``skydeck run sim --speed 1 --camera-width W --camera-height H
--camera-rate 30``, registered with a core; its renderer is whatever it finds (OpenGL through
EGL, else PyBullet's: its log says which).
"""

from __future__ import annotations

import threading
import time
from typing import Any

import httpx
from websockets.sync.client import connect

from benchmarks.processes import BenchError, Worker, free_port, wait_http, worker_env
from benchmarks.report import Result
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.sim import sim_argv
from benchmarks.topics import CoreHolder

__all__ = ["camera_family", "measure_camera"]

_SIZES = ((320, 240), (640, 480))

_RATE_HZ = 30.0
_WARMUP_S = 1.0
_FIRST_FRAME_S = 15.0


def measure_camera(core: CoreHolder, *, width: int, height: int, window_s: float, seed: int = 1) -> dict[str, Any]:
    """Frames a second a raw-image reader gets over ``window_s``, and the sim's pace meanwhile."""
    port = free_port()
    argv = sim_argv(port, seed=seed, world_args=["--boxes", "8", "--camera-width", str(width),
                                                  "--camera-height", str(height), "--camera-rate", str(_RATE_HZ)])  # fmt: skip
    argv[argv.index("--speed") + 1] = "1"
    url = f"http://127.0.0.1:{port}"
    frames: list[float] = []
    stop = threading.Event()

    def read() -> None:
        stream = f"ws://127.0.0.1:{port}/simulator/camera/image_raw?encoding=msgpack&queue=1"
        with connect(stream, max_size=None, open_timeout=10) as websocket:
            while not stop.is_set():
                try:
                    websocket.recv(timeout=0.5)
                except TimeoutError:
                    continue
                frames.append(time.monotonic())

    with Worker("camera-sim", argv=argv, env=worker_env(core.get())) as sim, httpx.Client(timeout=5.0) as client:
        wait_http(f"{url}/health", 60.0, what="simulator node", worker=sim)
        wait_http(f"{url}/clock", 30.0, what="simulator /clock", worker=sim)
        reader = threading.Thread(target=read, name="camera-reader", daemon=True)
        reader.start()
        deadline = time.monotonic() + _FIRST_FRAME_S
        while not frames and time.monotonic() < deadline:  # the renderer opens on the first reader
            time.sleep(0.05)
        time.sleep(_WARMUP_S)
        cpu0 = sim.cpu_seconds()
        sim0, wall0 = _sim_time_s(client, url)
        time.sleep(window_s)
        sim1, wall1 = _sim_time_s(client, url)
        cpu1 = sim.cpu_seconds()
        stop.set()
        reader.join(5.0)
    in_window = [t for t in frames if wall0 <= t <= wall1]
    if not in_window:
        raise BenchError(f"the {width}x{height} camera delivered no frame in {window_s:g} s")
    return {
        "fps": len(in_window) / (wall1 - wall0),
        "pace": (sim1 - sim0) / (wall1 - wall0),
        "sim_cpu": (cpu1 - cpu0) / (wall1 - wall0),
    }


def _sim_time_s(client: httpx.Client, url: str) -> tuple[float, float]:
    wall = time.monotonic()
    stamp = client.get(f"{url}/clock").json()
    return stamp["sec"] + stamp["nanosec"] * 1e-9, wall


def camera_family(core: CoreHolder, *, window_s: float, repetitions: int) -> Family:
    """The ``camera`` rows: frames a second delivered and the sim's pace, at 320x240 and 640x480."""

    def trial(width: int, height: int) -> Trial:
        return Trial(f"{width}x{height}", f"camera {width}x{height} at 30 Hz, speed 1",
                     lambda: measure_camera(core, width=width, height=height, window_s=window_s))  # fmt: skip

    trials = [trial(w, h) for w, h in _SIZES]

    def summarise(readings: Readings) -> list[Result]:
        rows = []
        for w, h in _SIZES:
            got = readings[f"{w}x{h}"]
            fps = Result(f"camera_fps_{w}x{h}", median_of(got, "fps"), "frames/s", "asked", _RATE_HZ,
                         target=">= 0.95 of 30 Hz" if w == 640 else "-", samples=[r["fps"] for r in got],
                         detail={"sim_cpu": median_of(got, "sim_cpu")})  # fmt: skip
            if w == 640:
                fps.met = fps.ratio is not None and fps.ratio >= 0.95
            pace = Result(f"camera_sim_pace_{w}x{h}", median_of(got, "pace"), "x real time", None, None,
                          target=">= 0.95 (speed 1, kept up while watched)" if w == 640 else "-",
                          samples=[r["pace"] for r in got])  # fmt: skip
            if w == 640:
                pace.met = (pace.value or 0) >= 0.95
            rows += [fps, pace]
        return rows

    names = tuple(f"camera_{kind}_{w}x{h}" for w, h in _SIZES for kind in ("fps", "sim_pace"))
    return Family("camera", trials, repetitions, summarise, rows=names)
