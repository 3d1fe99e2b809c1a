// visualization_msgs/Marker -> a three.js object, by type, with rviz's meaning of scale, colour
// and points. A shape of the same kind is updated in place (a 500-marker array re-sent at 5 Hz
// rebuilds nothing); anything that cannot be drawn is a BadData naming the field.

import * as THREE from "three";
import { BadData, rgba, setVector } from "./ros_math.js";
import { disposeObject, setSpriteText, solidMaterial, textSprite, unitGeometry } from "./shapes.js";

export const MARKER_TYPES = {
  0: "ARROW",
  1: "CUBE",
  2: "SPHERE",
  3: "CYLINDER",
  4: "LINE_STRIP",
  5: "LINE_LIST",
  6: "CUBE_LIST",
  7: "SPHERE_LIST",
  8: "POINTS",
  9: "TEXT_VIEW_FACING",
  10: "MESH_RESOURCE",
  11: "TRIANGLE_LIST",
};

const SOLIDS = { 1: "box", 2: "sphere", 3: "cylinder" };
const _scale = new THREE.Vector3();
const _a = new THREE.Vector3();
const _b = new THREE.Vector3();
const _x = new THREE.Vector3(1, 0, 0);

/** Warnings that do not stop a marker from being drawn (rviz's, in its words where it has them). */
export function markerWarnings(m) {
  const warnings = [];
  const s = m.scale || {};
  const needs = m.type === 9 ? [s.z] : m.type === 4 || m.type === 5 ? [s.x] : m.type === 8 ? [s.x, s.y] : [s.x, s.y, s.z];
  if (needs.some((v) => v === 0)) warnings.push("scale is 0 in a dimension it needs: nothing to see");
  const colored = Array.isArray(m.colors) && m.colors.length;
  if (!colored && m.color && m.color.a === 0) warnings.push("color.a is 0: fully transparent");
  return warnings;
}

/**
 * The object for marker `m`, in its pose's frame (the caller places it): `previous` is updated in
 * place when it has the same type, else disposed and replaced.
 */
export function markerObject(m, previous) {
  const type = m.type;
  const name = MARKER_TYPES[type];
  if (name === undefined) throw new BadData(`unknown marker type ${JSON.stringify(type)}`);
  if (name === "MESH_RESOURCE") throw new BadData("MESH_RESOURCE markers are not drawn (no mesh loader in the browser)");
  setVector(_scale, m.scale, "scale");
  const [color, opacity] = rgba(m.color, "color");
  const reuse = previous && previous.userData.markerType === type;
  if (previous && !reuse) disposeObject(previous);
  let object;
  if (SOLIDS[type]) object = solid(reuse ? previous : null, SOLIDS[type], color, opacity);
  else if (name === "ARROW") object = arrow(m, reuse ? previous : null, color, opacity);
  else if (name === "TEXT_VIEW_FACING") object = text(m, reuse ? previous : null, color, opacity);
  else object = pointsShape(m, name, reuse ? previous : null, color, opacity);
  object.userData.markerType = type;
  object.visible = opacity > 0;
  return object;
}

function solid(previous, shape, color, opacity) {
  const mesh = previous || new THREE.Mesh(unitGeometry()[shape], solidMaterial(color, opacity));
  setMaterial(mesh.material, color, opacity);
  mesh.scale.copy(_scale);
  return mesh;
}

function setMaterial(material, color, opacity) {
  material.color.copy(color);
  const transparent = opacity < 1;
  if (material.transparent !== transparent) material.needsUpdate = true;
  material.transparent = transparent;
  material.opacity = opacity;
  material.depthWrite = !transparent;
}

/** ARROW: along the pose's +x with scale (length, width, height), or from points[0] to points[1]
 * with scale (shaft diameter, head diameter, head length). */
function arrow(m, previous, color, opacity) {
  const points = Array.isArray(m.points) ? m.points : [];
  const group = previous || new THREE.Group();
  if (!previous) {
    const material = solidMaterial(color, opacity);
    const { arrow: whole, shaft, cone } = unitGeometry();
    group.add(new THREE.Mesh(whole, material), new THREE.Mesh(shaft, material), new THREE.Mesh(cone, material));
  }
  const [whole, shaft, head] = group.children;
  setMaterial(whole.material, color, opacity);
  group.position.set(0, 0, 0);
  group.quaternion.identity();
  if (points.length < 2) {
    whole.visible = true;
    shaft.visible = head.visible = false;
    whole.scale.copy(_scale);
    return group;
  }
  setVector(_a, points[0], "points[0]");
  setVector(_b, points[1], "points[1]");
  const length = _b.distanceTo(_a);
  const headLength = _scale.z > 0 ? Math.min(_scale.z, length) : 0.23 * length;
  whole.visible = false;
  shaft.visible = head.visible = length > 0;
  group.position.copy(_a);
  if (length > 0) group.quaternion.setFromUnitVectors(_x, _b.sub(_a).divideScalar(length));
  shaft.scale.set(Math.max(length - headLength, 1e-6), _scale.x, _scale.x);
  head.scale.set(Math.max(headLength, 1e-6), _scale.y, _scale.y);
  head.position.set(length - headLength, 0, 0);
  return group;
}

function text(m, previous, color, opacity) {
  const css = `#${color.getHexString()}`;
  const label = typeof m.text === "string" ? m.text : "";
  const height = _scale.z;
  const sprite = previous || textSprite(label, css, height);
  setSpriteText(sprite, label, css, height);
  sprite.material.opacity = opacity;
  return sprite;
}

/** LINE_STRIP, LINE_LIST, POINTS, CUBE_LIST, SPHERE_LIST, TRIANGLE_LIST: built from `points`
 * (and `colors`, one per point, when given). */
function pointsShape(m, name, previous, color, opacity) {
  const points = Array.isArray(m.points) ? m.points : [];
  const colors = Array.isArray(m.colors) && m.colors.length ? m.colors : null;
  if (colors && colors.length !== points.length) {
    throw new BadData(`${colors.length} colors for ${points.length} points (give none or one per point)`);
  }
  if (name === "LINE_LIST" && points.length % 2) throw new BadData(`LINE_LIST needs an even number of points, not ${points.length}`);
  if (name === "TRIANGLE_LIST" && points.length % 3) throw new BadData(`TRIANGLE_LIST needs a multiple of 3 points, not ${points.length}`);
  const positions = new Float32Array(points.length * 3);
  points.forEach((p, i) => setVector(_a, p, `points[${i}]`).toArray(positions, i * 3));
  let vertexColors = null;
  let alpha = opacity;
  if (colors) {
    vertexColors = new Float32Array(points.length * 3);
    alpha = 0;
    colors.forEach((c, i) => {
      const [rgb, a] = rgba(c, `colors[${i}]`);
      rgb.toArray(vertexColors, i * 3);
      alpha = Math.max(alpha, a);
    });
  }
  if (name === "CUBE_LIST" || name === "SPHERE_LIST") return instanced(name, previous, positions, vertexColors, color, alpha);
  const object = previous || newPointsObject(name, !!vertexColors);
  const geometry = object.geometry;
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  if (vertexColors) geometry.setAttribute("color", new THREE.BufferAttribute(vertexColors, 3));
  else geometry.deleteAttribute("color");
  geometry.computeBoundingSphere();
  const material = object.material;
  if (material.vertexColors !== !!vertexColors) {
    material.vertexColors = !!vertexColors;
    material.needsUpdate = true;
  }
  setMaterial(material, vertexColors ? new THREE.Color(1, 1, 1) : color, alpha);
  if (name === "POINTS") material.size = Math.max(_scale.x, 1e-4);
  return object;
}

function newPointsObject(name, withColors) {
  const geometry = new THREE.BufferGeometry();
  if (name === "POINTS") return new THREE.Points(geometry, new THREE.PointsMaterial({ sizeAttenuation: true, vertexColors: withColors }));
  if (name === "TRIANGLE_LIST") {
    return new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ side: THREE.DoubleSide, vertexColors: withColors }));
  }
  // Lines are one pixel wide whatever scale.x says: WebGL draws no wider lines.
  const material = new THREE.LineBasicMaterial({ vertexColors: withColors });
  return name === "LINE_STRIP" ? new THREE.Line(geometry, material) : new THREE.LineSegments(geometry, material);
}

const _instance = new THREE.Matrix4();
const _position = new THREE.Vector3();
const _identity = new THREE.Quaternion();
const _white = new THREE.Color(1, 1, 1);
const _color = new THREE.Color();

function instanced(name, previous, positions, vertexColors, color, opacity) {
  const count = positions.length / 3;
  let mesh = previous;
  if (!mesh || mesh.instanceMatrix.count < count) {
    if (mesh) disposeObject(mesh);
    const geometry = unitGeometry()[name === "CUBE_LIST" ? "box" : "sphere"];
    mesh = new THREE.InstancedMesh(geometry, solidMaterial(color, opacity), Math.max(count, 1));
  }
  for (let i = 0; i < count; i++) {
    mesh.setMatrixAt(i, _instance.compose(_position.fromArray(positions, i * 3), _identity, _scale));
    mesh.setColorAt(i, vertexColors ? _color.fromArray(vertexColors, i * 3) : _white);
  }
  mesh.count = count;
  mesh.instanceMatrix.needsUpdate = true;
  if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
  mesh.computeBoundingSphere();
  setMaterial(mesh.material, vertexColors ? _white : color, opacity);
  return mesh;
}
