"""The 3D view's own logic, run in Chromium on the page's real modules (no simulator): the TF
tree's lookups, the saved-view checks, markers that cannot be drawn, the scan's filtering.

The page is the dashboard served by a real core, so the modules load exactly as users get them
(import map, three.js from the core); each test imports what it needs with ``import()``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

from tests.web_ui.conftest import open_dashboard
from tests.web_ui.system import System, started

pytestmark = [pytest.mark.browser, pytest.mark.timeout(60)]


@pytest.fixture(scope="module")
def system() -> Iterator[System]:
    with started() as running:
        yield running


@pytest.fixture(scope="module")
def page(system: System, browser: object) -> Iterator[object]:
    with open_dashboard(browser, system.url, "window.skydeck !== undefined") as (page, recorder):
        yield page
        assert recorder.errors == []


TREE = """
const THREE = await import('three');
const { TfTree } = await import('/static/js/view3d/tf_tree.js');
const tree = new TfTree();
const edge = (parent, child, x, y, yaw, sec = 0, z = 0) => ({
  header: { frame_id: parent, stamp: { sec, nanosec: 0 } },
  child_frame_id: child,
  transform: { translation: { x, y, z }, rotation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) } },
});
const where = (target, source, stamp = null) => {
  const found = tree.lookup(target, source, stamp, new THREE.Matrix4());
  if (found.error) return found;
  const p = new THREE.Vector3().setFromMatrixPosition(found.matrix);
  return { x: p.x, y: p.y, z: p.z, ahead: found.ahead, clockNote: found.clockNote };
};
"""


def run(page, body: str) -> dict[str, object]:  # type: ignore[no-untyped-def]
    return page.evaluate(f"async () => {{ {TREE} {body} }}")  # type: ignore[no-any-return]


def test_lookup_composes_a_chain_and_inverts_it(page) -> None:  # type: ignore[no-untyped-def]
    result = run(
        page,
        """
        tree.applyMessage({ transforms: [edge('map', 'odom', 1, 2, Math.PI / 2)] }, true);
        tree.applyMessage({ transforms: [edge('base_link', 'laser', 0.1, 0, 0, 0, 0.2)] }, true);
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 3, 0, Math.PI / 2, 10)] }, false);
        return { laser: where('map', 'laser'), back: where('laser', 'map'), same: where('odom', 'odom') };
        """,
    )
    # odom at (1, 2) turned 90°: base_link at odom (3, 0) is map (1, 5), facing -x (90° + 90°);
    # the laser 0.1 ahead of it is at map (0.9, 5, 0.2).
    laser = result["laser"]
    assert math.isclose(laser["x"], 0.9, abs_tol=1e-9) and math.isclose(laser["y"], 5.0, abs_tol=1e-9)
    assert math.isclose(laser["z"], 0.2, abs_tol=1e-9)
    back = result["back"]  # map's origin seen from the laser, which faces -x at (0.9, 5)
    assert math.isclose(back["x"], 0.9, abs_tol=1e-9) and math.isclose(back["y"], 5.0, abs_tol=1e-9)
    assert result["same"] == {"x": 0, "y": 0, "z": 0, "ahead": 0, "clockNote": ""}


def test_lookup_interpolates_at_a_stamp_and_says_when_it_is_ahead(page) -> None:  # type: ignore[no-untyped-def]
    result = run(
        page,
        """
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 0, 0, 0, 100)] }, false);
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 2, 0, 0, 101)] }, false);
        const between = where('odom', 'base_link', 100.25);
        const ahead = where('odom', 'base_link', 101.5);
        const latest = where('odom', 'base_link', null);
        const otherClock = where('odom', 'base_link', 5000);
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 7, 0, 0, 3)] }, false);  // time went back
        const afterReset = where('odom', 'base_link', 100.25);
        return { between, ahead, latest, otherClock, afterReset };
        """,
    )
    assert math.isclose(result["between"]["x"], 0.5, abs_tol=1e-9)
    assert result["between"]["ahead"] == 0
    assert math.isclose(result["ahead"]["ahead"], 0.5, abs_tol=1e-9) and result["ahead"]["x"] == 2
    assert result["latest"]["x"] == 2
    assert "outside the transforms' times" in result["otherClock"]["clockNote"]
    assert result["afterReset"]["x"] == 7, "a simulator reset starts the history again"


def test_lookup_says_why_there_is_no_transform(page) -> None:  # type: ignore[no-untyped-def]
    result = run(
        page,
        """
        tree.applyMessage({ transforms: [edge('map', 'a', 1, 0, 0)] }, true);
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 1, 0, 0)] }, true);
        const unconnected = where('map', 'base_link');
        const unknown = where('map', 'nowhere');
        const noFixed = where('world', 'a');
        const before = tree.structureVersion;
        tree.applyMessage({ transforms: [edge('a', 'map', 1, 0, 0)] }, true);  // a loop
        const loop = where('map', 'a');
        const bad = { header: { frame_id: 'map' }, child_frame_id: 'b', transform: { translation: { x: 0, y: 0, z: 0 }, rotation: { x: 0, y: 0, z: 0, w: 0 } } };
        tree.applyMessage({ transforms: [bad, edge('map', 'c', 0, 0, 0)] }, true);
        return { unconnected, unknown, noFixed, loop, grew: tree.structureVersion > before,
                 rejected: tree.rejected, reason: tree.lastRejection, frames: tree.frames() };
        """,
    )
    assert result["unconnected"]["error"] == (
        "No transform from [base_link] to [map]: they are in unconnected trees (base_link under odom, map under map)"
    )
    assert result["unknown"]["error"] == "Frame [nowhere] does not exist"
    assert result["noFixed"]["error"] == "Fixed frame [world] does not exist"
    assert "loop" in result["loop"]["error"]
    assert result["grew"] is True
    assert result["rejected"] == 1 and "zero length" in result["reason"], "one bad transform skipped"
    assert "c" in result["frames"] and "b" not in result["frames"], "the good one in the same message applied"


def test_default_fixed_frame_is_the_root_of_the_biggest_tree(page) -> None:  # type: ignore[no-untyped-def]
    result = run(
        page,
        """
        const picks = [tree.defaultFixedFrame()];
        tree.addFrame('zeta'); tree.addFrame('odom');
        picks.push(tree.defaultFixedFrame());  // a tie of lone frames: odom before the rest
        tree.addFrame('map');
        picks.push(tree.defaultFixedFrame());  // map before odom
        tree.applyMessage({ transforms: [edge('odom', 'base_link', 0, 0, 0), edge('base_link', 'laser', 0, 0, 0)] }, true);
        picks.push(tree.defaultFixedFrame());  // the biggest tree wins
        tree.applyMessage({ transforms: [edge('map', 'odom', 0, 0, 0)] }, true);
        picks.push(tree.defaultFixedFrame());
        return picks;
        """,
    )
    assert result == ["map", "odom", "map", "odom", "map"]


def test_saved_views_are_checked_field_by_field(page) -> None:  # type: ignore[no-untyped-def]
    result = page.evaluate(
        """async () => {
        const { checkDocument } = await import('/static/js/view3d/persistence.js');
        const known = (type) => type === 'sensor_msgs/msg/LaserScan';
        const attempt = (doc) => { try { return checkDocument(doc, known); } catch (e) { return { error: e.message }; } };
        const good = { format: 'skydeck-view3d', version: 1, fixedFrame: 'odom',
          camera: { position: [1, 2, 3], target: [0, 0, 0], follow: true }, grid: false,
          displays: [{ topic: '/scan', type: 'sensor_msgs/msg/LaserScan', color: '#112233', visible: false, options: { size: 3 } }] };
        return {
          good: attempt(good),
          notView: attempt({ format: 'rviz' }),
          future: attempt({ ...good, version: 2 }),
          list: attempt([]),
          mixed: attempt({ ...good, fixedFrame: 'no spaces please', camera: { position: [1, 2] },
            displays: [...good.displays, good.displays[0], { topic: 'scan', type: 'x' },
                       { topic: '/s', type: 'std_msgs/msg/String' }, { topic: '/scan2', type: 'sensor_msgs/msg/LaserScan', color: 'red' }] }),
        };
    }"""
    )
    assert result["good"]["warnings"] == []
    assert result["good"]["settings"]["displays"][0]["options"] == {"size": 3}
    assert result["good"]["settings"]["camera"]["follow"] is True and result["good"]["settings"]["grid"] is False
    assert "not a Skydeck 3D view file" in result["notView"]["error"]
    assert "version 2" in result["future"]["error"]
    assert result["list"]["error"] == "not a JSON object"
    mixed = result["mixed"]
    assert mixed["settings"]["fixedFrame"] is None and mixed["settings"]["camera"] is None
    assert [d["topic"] for d in mixed["settings"]["displays"]] == ["/scan", "/scan2"]
    assert mixed["settings"]["displays"][1].get("color") is None, "a colour that is not #rrggbb is dropped"
    warnings = " | ".join(mixed["warnings"])
    for expected in (
        "fixedFrame is not a frame name",
        "camera is not",
        "/scan is there twice",
        "topic is not a ROS name",
        'no display for type "std_msgs/msg/String"',
    ):
        assert expected in warnings, (expected, warnings)


def test_markers_that_cannot_be_drawn_say_why(page) -> None:  # type: ignore[no-untyped-def]
    result = page.evaluate(
        """async () => {
        const { markerObject, markerWarnings } = await import('/static/js/view3d/marker_shapes.js');
        const base = { scale: { x: 1, y: 1, z: 1 }, color: { r: 1, g: 0, b: 0, a: 1 }, points: [], colors: [] };
        const why = (m) => { try { markerObject({ ...base, ...m }, null); return 'drawn'; } catch (e) { return e.message; } };
        return {
          unknown: why({ type: 42 }),
          mesh: why({ type: 10 }),
          oddList: why({ type: 5, points: [{ x: 0, y: 0, z: 0 }] }),
          colours: why({ type: 8, points: [{ x: 0, y: 0, z: 0 }], colors: [base.color, base.color] }),
          nanPoint: why({ type: 4, points: [{ x: NaN, y: 0, z: 0 }] }),
          cubeList: why({ type: 6, points: [{ x: 0, y: 0, z: 0 }, { x: 1, y: 0, z: 0 }] }),
          warnings: markerWarnings({ ...base, type: 1, scale: { x: 0, y: 1, z: 1 }, color: { r: 1, g: 1, b: 1, a: 0 } }),
        };
    }"""
    )
    assert result["unknown"] == "unknown marker type 42"
    assert "MESH_RESOURCE" in result["mesh"]
    assert result["oddList"] == "LINE_LIST needs an even number of points, not 1"
    assert result["colours"] == "2 colors for 1 points (give none or one per point)"
    assert result["nanPoint"] == "points[0] is not a finite x, y, z"
    assert result["cubeList"] == "drawn"
    assert len(result["warnings"]) == 2


def test_a_scan_draws_only_real_returns(page) -> None:  # type: ignore[no-untyped-def]
    result = page.evaluate(
        """async () => {
        const { createDisplay } = await import('/static/js/view3d/displays/index.js');
        const d = createDisplay('/s', 'sensor_msgs/msg/LaserScan', {}, {});
        d.receive({ header: { frame_id: 'laser' }, angle_min: 0, angle_increment: Math.PI / 2, range_min: 0.2, range_max: 5,
                    ranges: [1, 0, 0.1, 6, 2, null] });
        d.update({ now: 0, fixedFrame: 'laser', lookup: (f, s, out) => ({ matrix: out.identity(), clockNote: '', ahead: 0 }) });
        return { points: d.drawn().points, status: d.status().entries.map((e) => e.text) };
    }"""
    )
    # beam 0 at 1 m ahead; beam 4 (angle 2π) at 2 m ahead; 0.0, below range_min, above range_max
    # and a non-number are not drawn.
    assert result["points"] == [[1, 0, 0], [2, 0, 0]]
    assert "1 ranges were not numbers and were skipped" in result["status"]


def test_a_scan_is_coloured_by_range_from_red_near_to_violet_far(page) -> None:  # type: ignore[no-untyped-def]
    result = page.evaluate(
        """async () => {
        const { createDisplay } = await import('/static/js/view3d/displays/index.js');
        const d = createDisplay('/s', 'sensor_msgs/msg/LaserScan', { color: '#00ff00' }, {});
        d.receive({ header: { frame_id: 'laser' }, angle_min: 0, angle_increment: Math.PI / 2, range_min: 0.2, range_max: 5,
                    ranges: [0.2, 2.6, 5, 0] });
        d.update({ now: 0, fixedFrame: 'laser', lookup: (f, s, out) => ({ matrix: out.identity(), clockNote: '', ahead: 0 }) });
        const colours = () => Array.from(d.geometry.attributes.color.array.slice(0, 9), (c) => Math.round(c * 1000) / 1000);
        const byRange = colours();
        d.setOption('byRange', false);
        return { byRange, flat: colours() };
    }"""
    )
    red, middle, violet = (result["byRange"][i : i + 3] for i in (0, 3, 6))
    assert red == [1, 0, 0], "range_min is red"
    assert violet == [0.5, 0, 1], "range_max is violet (hue 270)"
    assert middle[1] > 0.9 and middle[0] < 0.1, "half way is green-cyan (hue 135)"
    assert result["flat"] == [0, 1, 0] * 3, "colour by range off: the display's colour"
