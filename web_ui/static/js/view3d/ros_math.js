// ROS message fields -> three.js values, checked: every reader of a message goes through these,
// so a NaN, a zero-length quaternion or a missing field becomes a BadData with a reason that a
// display shows, never a broken scene.

import * as THREE from "three";

/** A message (or part of one) that cannot be drawn; `message` says why, for the display's note. */
export class BadData extends Error {}

const isNumber = (value) => typeof value === "number" && Number.isFinite(value);

/** out.set(v.x, v.y, v.z) when all are finite numbers (z may be absent: Point32 in 2D). */
export function setVector(out, v, what) {
  if (!v || !isNumber(v.x) || !isNumber(v.y) || !(v.z === undefined || isNumber(v.z))) {
    throw new BadData(`${what} is not a finite x, y, z`);
  }
  return out.set(v.x, v.y, v.z ?? 0);
}

/** out = q normalised; a zero-length or non-finite quaternion is BadData (rviz refuses it too). */
export function setQuaternion(out, q, what = "orientation") {
  if (!q || !isNumber(q.x) || !isNumber(q.y) || !isNumber(q.z) || !isNumber(q.w)) {
    throw new BadData(`${what} is not a finite quaternion`);
  }
  const norm = Math.hypot(q.x, q.y, q.z, q.w);
  if (norm < 1e-6) throw new BadData(`${what} is a quaternion of zero length`);
  return out.set(q.x / norm, q.y / norm, q.z / norm, q.w / norm);
}

const _position = new THREE.Vector3();
const _rotation = new THREE.Quaternion();
const _unit = new THREE.Vector3(1, 1, 1);

/** out = the matrix of a geometry_msgs/Pose. */
export function setPoseMatrix(out, pose, what = "pose") {
  if (!pose) throw new BadData(`${what} is missing`);
  setVector(_position, pose.position, `${what}.position`);
  setQuaternion(_rotation, pose.orientation, `${what}.orientation`);
  return out.compose(_position, _rotation, _unit);
}

/** Seconds of a builtin_interfaces/Time; null for a zero or missing stamp ("the latest", as tf2). */
export function stampSeconds(stamp) {
  if (!stamp || !isNumber(stamp.sec)) return null;
  const seconds = stamp.sec + (isNumber(stamp.nanosec) ? stamp.nanosec : 0) * 1e-9;
  return seconds > 0 ? seconds : null;
}

/** Seconds of a builtin_interfaces/Duration (0 when missing). */
export function durationSeconds(duration) {
  if (!duration || !isNumber(duration.sec)) return 0;
  return duration.sec + (isNumber(duration.nanosec) ? duration.nanosec : 0) * 1e-9;
}

/** A frame id as tf2 names it: without a leading slash ("/odom" is "odom"). */
export function frameName(frameId) {
  return typeof frameId === "string" ? frameId.replace(/^\/+/, "") : "";
}

/** {r, g, b, a} in 0..1 (std_msgs/ColorRGBA) -> [THREE.Color, opacity]; channels are clamped. */
export function rgba(color, what = "color") {
  if (!color || ![color.r, color.g, color.b, color.a].every(isNumber)) throw new BadData(`${what} is not finite`);
  const clamp = (v) => Math.min(1, Math.max(0, v));
  return [new THREE.Color(clamp(color.r), clamp(color.g), clamp(color.b)), clamp(color.a)];
}

/** The rainbow rviz uses for ranges and intensities: 0 -> red, 1 -> magenta-blue. */
export function rainbow(out, fraction) {
  const f = Math.min(1, Math.max(0, fraction));
  return out.setHSL((f * 270) / 360, 1, 0.5);
}
