"""The chase camera renders headless and encodes a real JPEG."""

from __future__ import annotations

import io
from collections.abc import Callable

import pytest
from PIL import Image

from sim_server.drone.camera import render_jpeg
from sim_server.drone.world import World


def test_renders_a_jpeg_of_the_requested_size(make_world: Callable[..., World]) -> None:
    world = make_world(seed=1)
    world.step(240)
    frame = render_jpeg(world)
    assert frame[:2] == b"\xff\xd8"  # JPEG start-of-image marker
    assert frame[-2:] == b"\xff\xd9"
    image = Image.open(io.BytesIO(frame))
    assert image.format == "JPEG"
    assert image.size == (320, 240)
    image = Image.open(io.BytesIO(render_jpeg(world, width=160, height=90, quality=40)))
    assert image.size == (160, 90)


def test_the_view_shows_colours_not_a_blank_frame(make_world: Callable[..., World]) -> None:
    world = make_world(seed=1)
    world.step(480)
    image = Image.open(io.BytesIO(render_jpeg(world))).convert("RGB")
    colours = image.getcolors(maxcolors=320 * 240)
    assert colours is not None and len(colours) > 50
    # the drone sits in the middle of the chase view: its dark hull is there
    cx, cy = image.size[0] // 2, image.size[1] // 2
    centre = [image.getpixel((x, y)) for x in range(cx - 6, cx + 7) for y in range(cy - 6, cy + 7)]
    assert min(sum(pixel) for pixel in centre) < 200  # type: ignore[arg-type]


@pytest.mark.parametrize("size", [(0, 240), (320, 5000)])
def test_refuses_impossible_sizes(make_world: Callable[..., World], size: tuple[int, int]) -> None:
    with pytest.raises(ValueError, match="image size"):
        render_jpeg(make_world(seed=1, boxes=0), *size)
