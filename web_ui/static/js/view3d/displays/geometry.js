// Displays of geometry_msgs and nav_msgs/Path: a point as a sphere, a pose as an arrow, a pose
// array as arrows, a polygon as a closed line, a path as a line through its poses.

import * as THREE from "three";
import { BadData, setPoseMatrix, setVector } from "../ros_math.js";
import { solidMaterial, unitGeometry } from "../shapes.js";
import { Display, worldPoint } from "./display.js";

const _matrix = new THREE.Matrix4();
const _scale = new THREE.Matrix4();
const _origin = new THREE.Vector3();

/** geometry_msgs/PointStamped: a sphere (rviz's Point display). */
export class PointDisplay extends Display {
  static options = { radius: { label: "radius (m)", type: "number", default: 0.2, min: 0.01, max: 5, step: 0.05 } };

  constructor(...args) {
    super(...args);
    this.sphere = new THREE.Mesh(unitGeometry().sphere, solidMaterial(this.color));
    this.sphere.visible = false;
    this.root.add(this.sphere);
    this.restyle();
  }

  apply(msg, ctx) {
    const { frame, stamp } = this.headerFrame(msg.header);
    setVector(this.sphere.position, msg.point, "point");
    this.sphere.visible = true;
    this.place(ctx, frame, stamp, this.root);
  }

  restyle() {
    this.sphere.material.color.set(this.color);
    this.sphere.scale.setScalar(this.options.radius * 2);
  }

  drawn() {
    return this.sphere.visible ? { objects: 1, points: [worldPoint(this.sphere, _origin)] } : { objects: 0, points: [] };
  }
}

/** Arrows along +x of each pose, drawn as one instanced mesh (a pose, or many). */
class ArrowsDisplay extends Display {
  static options = { length: { label: "arrow length (m)", type: "number", default: 1, min: 0.05, max: 20, step: 0.1 } };

  constructor(...args) {
    super(...args);
    this.poses = []; // Matrix4 per pose, in the message frame
    this.arrows = null;
    this._build(1);
  }

  _build(capacity) {
    if (this.arrows) {
      this.arrows.removeFromParent();
      this.arrows.material.dispose();
      this.arrows.dispose();
    }
    this.arrows = new THREE.InstancedMesh(unitGeometry().arrow, solidMaterial(this.color), capacity);
    this.arrows.count = 0;
    this.root.add(this.arrows);
  }

  setPoses(poses) {
    const matrices = poses.map((pose, i) => setPoseMatrix(new THREE.Matrix4(), pose, poses.length > 1 ? `poses[${i}]` : "pose"));
    if (matrices.length > this.arrows.instanceMatrix.count) this._build(Math.max(matrices.length, this.arrows.instanceMatrix.count * 2));
    this.poses = matrices;
    this.restyle();
  }

  restyle() {
    const length = this.options.length;
    _scale.makeScale(length, length * 0.2, length * 0.2);
    this.poses.forEach((pose, i) => this.arrows.setMatrixAt(i, _matrix.multiplyMatrices(pose, _scale)));
    this.arrows.count = this.poses.length;
    this.arrows.instanceMatrix.needsUpdate = true;
    this.arrows.computeBoundingSphere();
    this.arrows.material.color.set(this.color);
  }

  drawn() {
    const points = this.poses.map((pose) => worldPoint(this.root, _origin.clone().setFromMatrixPosition(pose)));
    return { objects: this.poses.length, points };
  }
}

/** geometry_msgs/PoseStamped: one arrow. */
export class PoseDisplay extends ArrowsDisplay {
  apply(msg, ctx) {
    const { frame, stamp } = this.headerFrame(msg.header);
    this.setPoses([msg.pose]);
    this.place(ctx, frame, stamp, this.root);
  }
}

/** geometry_msgs/PoseArray: an arrow per pose (the seed's /simulator/boxes). */
export class PoseArrayDisplay extends ArrowsDisplay {
  static rate = 10;
  static options = { length: { ...ArrowsDisplay.options.length, default: 0.5 } };

  apply(msg, ctx) {
    const { frame, stamp } = this.headerFrame(msg.header);
    if (!Array.isArray(msg.poses)) throw new BadData("poses is not a list");
    this.setPoses(msg.poses);
    this.place(ctx, frame, stamp, this.root);
  }
}

/** A line through points, with a dot on each: polygons (closed) and paths (open). */
class LineDisplay extends Display {
  static rate = 10;
  static closed = false;

  constructor(...args) {
    super(...args);
    this.geometry = new THREE.BufferGeometry();
    this.line = new (this.constructor.closed ? THREE.LineLoop : THREE.Line)(this.geometry, new THREE.LineBasicMaterial());
    this.dots = new THREE.Points(this.geometry, new THREE.PointsMaterial({ size: 6, sizeAttenuation: false }));
    this.root.add(this.line, this.dots);
    this.vertices = [];
    this.restyle();
  }

  setVertices(points, what) {
    const vertices = points.map((p, i) => setVector(new THREE.Vector3(), p, `${what}[${i}]`));
    this.vertices = vertices;
    this.geometry.setFromPoints(vertices);
    this.geometry.computeBoundingSphere();
  }

  restyle() {
    this.line.material.color.set(this.color);
    this.dots.material.color.set(this.color);
  }

  drawn() {
    return { objects: this.vertices.length ? 1 : 0, points: this.vertices.map((v) => worldPoint(this.root, v)) };
  }
}

/** geometry_msgs/Polygon (no header: drawn in the fixed frame, with a note) and PolygonStamped. */
export class PolygonDisplay extends LineDisplay {
  static closed = true;

  apply(msg, ctx) {
    const stamped = this.type.endsWith("/PolygonStamped");
    let place;
    if (stamped) {
      place = this.headerFrame(msg.header);
    } else {
      place = { frame: null, stamp: null };
      this.setStatus("Frame", "ok", "a Polygon has no header: drawn in the fixed frame");
    }
    const polygon = stamped ? msg.polygon : msg;
    if (!polygon || !Array.isArray(polygon.points)) throw new BadData("points is not a list");
    this.setVertices(polygon.points, "points");
    this.place(ctx, place.frame, place.stamp, this.root);
  }
}

/** nav_msgs/Path: a line through its poses, all in the path's header frame (as rviz). */
export class PathDisplay extends LineDisplay {
  apply(msg, ctx) {
    const { frame, stamp } = this.headerFrame(msg.header);
    if (!Array.isArray(msg.poses)) throw new BadData("poses is not a list");
    this.setVertices(
      msg.poses.map((p) => (p && p.pose ? p.pose.position : null)),
      "poses",
    );
    this.place(ctx, frame, stamp, this.root);
  }
}
