"""Where the 3D view draws a point, computed by the tests themselves: three.js's perspective
camera (a pinhole, z up, looking at its orbit target) from the camera the page reports
(``window.skydeck.view3d().camera``: position, target, vertical field of view, canvas size)."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["FOLLOWED_MODEL_PX", "MIN_FILLED", "MIN_MODEL_PX", "MIN_SPAN", "Camera", "measure_world", "report"]

# What "framed on the world" means in the tests of both worlds.
MIN_FILLED = 0.3  # of the canvas's area: a square floor seen at 45 degrees is a diamond, half its box
MIN_SPAN = 0.85  # of the canvas's width or height, spanned by the world
MIN_MODEL_PX = 36  # the drone or the robot at open
FOLLOWED_MODEL_PX = 60  # after Follow, at true size


class Camera:
    """three.js's perspective camera as the snapshot gives it: z up, looking at the target."""

    def __init__(self, snapshot: dict[str, Any]) -> None:
        self.position = snapshot["position"]
        target = snapshot["target"]
        self.width, self.height = snapshot["canvas"]
        self.tan = math.tan(math.radians(snapshot["fov"]) / 2)
        self.forward = _unit(_sub(target, self.position))
        self.right = _unit(_cross(self.forward, [0.0, 0.0, 1.0]))
        self.up = _cross(self.right, self.forward)

    def pixel(self, point: list[float]) -> tuple[float, float]:
        """Where ``point`` is drawn on the canvas (pixels from its top left)."""
        d = _sub(point, self.position)
        depth = _dot(d, self.forward)
        if depth <= 0:
            raise AssertionError(f"{point} is behind the camera")
        x = _dot(d, self.right) / (depth * self.tan * self.width / self.height)
        y = _dot(d, self.up) / (depth * self.tan)
        return (x + 1) / 2 * self.width, (1 - y) / 2 * self.height

    def inside(self, pixel: tuple[float, float]) -> bool:
        return 0 <= pixel[0] <= self.width and 0 <= pixel[1] <= self.height

    def span_px(self, point: list[float], metres: float) -> float:
        """How many pixels ``metres`` across the screen at ``point`` spans."""
        half = [c * metres / 2 for c in self.right]
        (x0, y0), (x1, y1) = self.pixel(_sub(point, half)), self.pixel([p + h for p, h in zip(point, half, strict=True)])
        return math.hypot(x1 - x0, y1 - y0)


def _sub(a: list[float], b: list[float]) -> list[float]:
    return [x - y for x, y in zip(a, b, strict=True)]


def _dot(a: list[float], b: list[float]) -> float:
    return sum(x * y for x, y in zip(a, b, strict=True))


def _cross(a: list[float], b: list[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _unit(a: list[float]) -> list[float]:
    length = math.sqrt(_dot(a, a))
    return [x / length for x in a]


def _hull_area(points: list[tuple[float, float]]) -> float:
    hull: list[tuple[float, float]] = []
    for p in sorted(points) + sorted(points)[::-1][1:]:  # monotone chain, both halves
        while len(hull) >= 2 and (hull[-1][0] - hull[-2][0]) * (p[1] - hull[-2][1]) - (hull[-1][1] - hull[-2][1]) * (p[0] - hull[-2][0]) <= 0:
            hull.pop()
        hull.append(p)
    return abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(hull, hull[1:] + hull[:1], strict=True))) / 2


def measure_world(camera: Camera, half: float, height: float) -> dict[str, float]:
    """What the world's box (a square floor of half-size ``half``, ``height`` tall) covers."""
    corners = [camera.pixel([x, y, z]) for x in (-half, half) for y in (-half, half) for z in (0.0, height)]
    assert all(camera.inside(c) for c in corners), f"part of the world is off the canvas: {corners}"
    xs, ys = [c[0] for c in corners], [c[1] for c in corners]
    return {
        "filled": _hull_area(corners) / (camera.width * camera.height),
        "span_x": (max(xs) - min(xs)) / camera.width,
        "span_y": (max(ys) - min(ys)) / camera.height,
    }


def report(world: str, figures: dict[str, float]) -> None:
    """Print the figures (pytest -s shows them; docs/view3d.md quotes them)."""
    print(f"\n3D view at open, {world}: " + ", ".join(f"{k} {v:.2f}" for k, v in figures.items()))
