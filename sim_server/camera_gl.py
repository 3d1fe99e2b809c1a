"""The camera drawn with OpenGL: a world's PyBullet scene rendered by Mesa through EGL
(moderngl), headless, in a few milliseconds where PyBullet's software renderer takes a hundred.

The scene is read from PyBullet each frame: every body's visual shapes (boxes, cylinders,
spheres: what the worlds are built of), placed at their link frames, drawn with the view and
projection matrices given to PyBullet's own renderer (so a body appears where
:func:`sim_server.camera.render_rgb` with PyBullet's renderer shows it) and one light.
Deterministic: the same world state draws the same bytes.

Needs moderngl and a Mesa EGL driver (Debian's ``libegl1`` and ``libgl1-mesa-dri``: llvmpipe on
the CPU, no GPU needed). :func:`open_renderer` says why when either is missing;
:mod:`sim_server.camera` then falls back to PyBullet's renderer.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pybullet as p

from shared_models.errors import SkydeckError

__all__ = ["GlRenderer", "GlUnavailable", "open_renderer"]

# PyBullet's own renderer's background and light, so both renderers look alike.
_BACKGROUND = (1.0, 1.0, 1.0)
_LIGHT_DIRECTION = (0.4, 0.5, 0.77)  # towards the light, world frame (z up)
_AMBIENT = 0.55
_CYLINDER_SIDES = 24
_SPHERE_RINGS = 10

_VERTEX_SHADER = """
#version 330
uniform mat4 view_projection;
in vec3 position;
in vec3 normal;
in vec4 model_0;
in vec4 model_1;
in vec4 model_2;
in vec4 model_3;
in vec4 colour;
out vec3 world_normal;
out vec4 shade;
void main() {
    mat4 model = mat4(model_0, model_1, model_2, model_3);
    world_normal = mat3(model) * normal;
    shade = colour;
    gl_Position = view_projection * model * vec4(position, 1.0);
}
"""

_FRAGMENT_SHADER = """
#version 330
uniform vec3 light;
uniform float ambient;
in vec3 world_normal;
in vec4 shade;
out vec4 pixel;
void main() {
    float diffuse = max(dot(normalize(world_normal), light), 0.0);
    pixel = vec4(shade.rgb * (ambient + (1.0 - ambient) * diffuse), 1.0);
}
"""


class GlUnavailable(SkydeckError, RuntimeError):
    """No OpenGL here: moderngl is not installed or no EGL driver could make a context."""


def open_renderer() -> GlRenderer:
    """A renderer on a new headless EGL context; :class:`GlUnavailable` saying why not."""
    try:
        import moderngl
    except ImportError as error:
        raise GlUnavailable(f"moderngl is not installed ({error})") from None
    try:
        context = moderngl.create_standalone_context(backend="egl")  # type: ignore[arg-type]  # the stub is wrong: a str
    except Exception as error:  # moderngl and glcontext raise plain Exceptions for a missing driver
        raise GlUnavailable(
            f"no EGL OpenGL context ({error}): install libegl1 and libgl1-mesa-dri"
        ) from None
    return GlRenderer(context)


class GlRenderer:
    """Draws PyBullet scenes on one OpenGL context; not thread-safe (one per process)."""

    def __init__(self, context: Any) -> None:
        self._ctx = context
        self._program = context.program(vertex_shader=_VERTEX_SHADER, fragment_shader=_FRAGMENT_SHADER)
        self._program["light"].value = _normalised(_LIGHT_DIRECTION)
        self._program["ambient"].value = _AMBIENT
        self._meshes = {
            p.GEOM_BOX: self._mesh(_box()),
            p.GEOM_CYLINDER: self._mesh(_cylinder(_CYLINDER_SIDES)),
            p.GEOM_CAPSULE: self._mesh(_cylinder(_CYLINDER_SIDES)),  # drawn as its cylinder
            p.GEOM_SPHERE: self._mesh(_sphere(_SPHERE_RINGS)),
        }
        self._instances = context.buffer(reserve=64 * 20 * 4, dynamic=True)
        self._vaos = {
            kind: context.vertex_array(
                self._program,
                [
                    (vertices, "3f 3f", "position", "normal"),
                    (self._instances, "4f 4f 4f 4f 4f/i", "model_0", "model_1", "model_2", "model_3", "colour"),
                ],
            )
            for kind, (vertices, _) in self._meshes.items()
        }
        self._framebuffer: Any = None
        self._size = (0, 0)

    def close(self) -> None:
        """Free the context."""
        self._ctx.release()

    def render(
        self, client: int, view_matrix: Sequence[float], projection: Sequence[float], width: int, height: int
    ) -> bytes:
        """The scene of PyBullet client ``client`` seen through PyBullet's ``view_matrix`` and
        ``projection`` (``computeViewMatrix``, ``computeProjectionMatrixFOV``) as ``rgb8``:
        ``height`` rows of ``3 * width`` bytes, the top row first."""
        ctx = self._ctx
        if self._size != (width, height):
            if self._framebuffer is not None:
                self._framebuffer.release()
            self._framebuffer = ctx.simple_framebuffer((width, height), components=3)
            self._size = (width, height)
        framebuffer = self._framebuffer
        framebuffer.use()
        ctx.enable(ctx.DEPTH_TEST)
        ctx.disable(ctx.CULL_FACE)
        framebuffer.clear(*_BACKGROUND, 1.0, depth=1.0)
        # PyBullet's matrices are column-major (OpenGL's): as numpy rows they are transposed, so
        # the product is taken the other way round.
        view_rows = np.array(view_matrix, dtype="f4").reshape(4, 4)
        projection_rows = np.array(projection, dtype="f4").reshape(4, 4)
        self._program["view_projection"].write((view_rows @ projection_rows).tobytes())
        for kind, instances in _instances_by_kind(client).items():
            data = np.ascontiguousarray(instances, dtype="f4")
            if data.nbytes > self._instances.size:
                self._instances.orphan(data.nbytes)
            self._instances.write(data.tobytes())
            vertices, count = self._meshes[kind]
            self._vaos[kind].render(instances=len(instances), vertices=count)
        pixels = np.frombuffer(framebuffer.read(components=3, alignment=1), dtype=np.uint8)
        return pixels.reshape(height, width, 3)[::-1].tobytes()  # OpenGL's first row is the bottom

    def _mesh(self, triangles: np.ndarray) -> tuple[Any, int]:
        return self._ctx.buffer(np.ascontiguousarray(triangles, dtype="f4").tobytes()), len(triangles)


def _instances_by_kind(client: int) -> dict[int, list[np.ndarray]]:
    """Each visual shape of the scene as a row: its model matrix (column-major) and colour."""
    out: dict[int, list[np.ndarray]] = {}
    for index in range(p.getNumBodies(physicsClientId=client)):
        body = p.getBodyUniqueId(index, physicsClientId=client)
        frames: dict[int, tuple[Any, Any]] = {}
        for shape in p.getVisualShapeData(body, physicsClientId=client):
            link, kind, dimensions, local_position, local_orientation, rgba = (
                shape[1], shape[2], shape[3], shape[5], shape[6], shape[7],
            )  # fmt: skip
            if kind not in (p.GEOM_BOX, p.GEOM_CYLINDER, p.GEOM_CAPSULE, p.GEOM_SPHERE) or rgba[3] <= 0.0:
                continue
            if link not in frames:
                frames[link] = _link_frame(client, body, link)
            position, orientation = p.multiplyTransforms(*frames[link], local_position, local_orientation)
            model = _model(position, orientation, _scale(kind, dimensions))
            out.setdefault(kind, []).append(np.concatenate([model.T.reshape(16), np.asarray(rgba, dtype="f4")]))
    return out


def _link_frame(client: int, body: int, link: int) -> tuple[Any, Any]:
    """The frame a link's visual shapes are placed in (the URDF link frame, not its centre of
    mass, which is what PyBullet reports for a base)."""
    if link >= 0:
        state = p.getLinkState(body, link, computeForwardKinematics=True, physicsClientId=client)
        return state[4], state[5]
    position, orientation = p.getBasePositionAndOrientation(body, physicsClientId=client)
    inertial_position, inertial_orientation = p.getDynamicsInfo(body, -1, physicsClientId=client)[3:5]
    inverse_position, inverse_orientation = p.invertTransform(inertial_position, inertial_orientation)
    return p.multiplyTransforms(position, orientation, inverse_position, inverse_orientation)


def _scale(kind: int, dimensions: Any) -> tuple[float, float, float]:
    if kind == p.GEOM_BOX:  # full extents
        return float(dimensions[0]), float(dimensions[1]), float(dimensions[2])
    if kind == p.GEOM_SPHERE:  # radius
        return (float(dimensions[0]),) * 3
    length, radius = float(dimensions[0]), float(dimensions[1])  # cylinder and capsule: along z
    return radius, radius, length


def _model(position: Any, orientation: Any, scale: tuple[float, float, float]) -> np.ndarray:
    rotation = np.array(p.getMatrixFromQuaternion(orientation), dtype="f4").reshape(3, 3)
    model = np.eye(4, dtype="f4")
    model[:3, :3] = rotation * np.array(scale, dtype="f4")
    model[:3, 3] = position
    return model


def _normalised(vector: tuple[float, float, float]) -> tuple[float, float, float]:
    length = math.sqrt(sum(c * c for c in vector))
    x, y, z = (c / length for c in vector)
    return x, y, z


# -- unit meshes: (x, y, z, nx, ny, nz) per vertex, three per triangle ---------------------------


def _box() -> np.ndarray:
    """A cube of side 1 centred on the origin."""
    rows = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            normal = [0.0, 0.0, 0.0]
            normal[axis] = sign
            u, v = [(a, b) for a, b in ((0, 1), (1, 2), (0, 2)) if axis not in (a, b)][0]
            corners = []
            for du, dv in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
                corner = [0.0, 0.0, 0.0]
                corner[axis], corner[u], corner[v] = 0.5 * sign, du, dv
                corners.append(corner)
            for i in (0, 1, 2, 0, 2, 3):
                rows.append([*corners[i], *normal])
    return np.array(rows, dtype="f4")


def _cylinder(sides: int) -> np.ndarray:
    """Radius 1, height 1, along z, centred on the origin."""
    rows = []
    for i in range(sides):
        a0, a1 = math.tau * i / sides, math.tau * (i + 1) / sides
        c0, s0, c1, s1 = math.cos(a0), math.sin(a0), math.cos(a1), math.sin(a1)
        bottom0, bottom1, top0, top1 = (c0, s0, -0.5), (c1, s1, -0.5), (c0, s0, 0.5), (c1, s1, 0.5)
        for point, normal in ((bottom0, (c0, s0, 0)), (bottom1, (c1, s1, 0)), (top1, (c1, s1, 0)),
                              (bottom0, (c0, s0, 0)), (top1, (c1, s1, 0)), (top0, (c0, s0, 0))):  # fmt: skip
            rows.append([*point, *normal])
        for z in (-0.5, 0.5):
            for point in ((0.0, 0.0, z), (c0, s0, z), (c1, s1, z)):
                rows.append([*point, 0.0, 0.0, math.copysign(1.0, z)])
    return np.array(rows, dtype="f4")


def _sphere(rings: int) -> np.ndarray:
    """Radius 1, centred on the origin (normals are the positions)."""
    rows = []
    sectors = 2 * rings

    def point(ring: int, sector: int) -> tuple[float, float, float]:
        theta, phi = math.pi * ring / rings, math.tau * sector / sectors
        return math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)

    for ring in range(rings):
        for sector in range(sectors):
            a, b = point(ring, sector), point(ring + 1, sector)
            c, d = point(ring + 1, sector + 1), point(ring, sector + 1)
            for vertex in (a, b, c, a, c, d):
                rows.append([*vertex, *vertex])
    return np.array(rows, dtype="f4")
