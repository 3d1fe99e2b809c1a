// The drone world in 3D: the ground and the square control flies in (the core's numbers from
// /api/config), the boxes of /simulator/boxes with their full orientation, and the drone of
// /drone/pose, tilted as it flies. Everything is in the frame the topics name (`map`).

import * as THREE from "three";
import { TopicSocket } from "../../api.js";
import { BadData, frameName, setPoseMatrix } from "../ros_math.js";
import { disposeObject, fitScale, solidMaterial, unitGeometry } from "../shapes.js";

const COLORS = { ground: 0x141d26, arena: 0x3b4b5c, box: 0xa98552, boxEdge: 0xd9b27a, drone: 0x61afef, front: 0xffb74d };

const DRONE_SPAN_M = 0.55 + 0.24; // motor to motor, plus a rotor's diameter
const SKID_DEPTH_M = 0.1; // from the body's centre to the bottom of its skids
const FOLLOW_DISTANCE_M = 5; // Follow brings the camera this close: the drone about 70 px across
const ARENA_HEIGHT_M = 3; // framed above the ground: the boxes and the drone at its altitude

/** A quadrotor about the Iris's size (0.55 m motor to motor): a body with a nose, two arms in an
 * x, a motor and a rotor disc at each end (the front two orange) and two landing skids. */
function droneModel() {
  const group = new THREE.Group();
  const { box, cylinder, sphere } = unitGeometry();
  const body = new THREE.Mesh(box, solidMaterial(COLORS.drone));
  body.scale.set(0.22, 0.14, 0.08);
  const nose = new THREE.Mesh(sphere, solidMaterial(COLORS.front));
  nose.scale.set(0.06, 0.06, 0.05);
  nose.position.set(0.12, 0, 0);
  group.add(body, nose);
  const arm = solidMaterial(0x9aa7b4);
  for (const angle of [Math.PI / 4, -Math.PI / 4]) {
    const rod = new THREE.Mesh(box, arm);
    rod.scale.set(0.55, 0.03, 0.025);
    rod.rotation.z = angle;
    group.add(rod);
  }
  for (const [sx, sy] of [[1, 1], [1, -1], [-1, 1], [-1, -1]]) {
    const motor = new THREE.Mesh(cylinder, arm);
    motor.scale.set(0.045, 0.045, 0.06);
    motor.position.set(sx * 0.195, sy * 0.195, 0.02);
    const rotor = new THREE.Mesh(cylinder, solidMaterial(sx > 0 ? COLORS.front : 0xd0d8e0, 0.75));
    rotor.scale.set(0.24, 0.24, 0.012);
    rotor.position.set(sx * 0.195, sy * 0.195, 0.055);
    group.add(motor, rotor);
  }
  for (const side of [1, -1]) {
    const skid = new THREE.Mesh(box, arm);
    skid.scale.set(0.24, 0.015, 0.015);
    skid.position.set(0, side * 0.08, -0.09);
    group.add(skid);
  }
  return group;
}

export class DroneWorld {
  constructor(arena, tf) {
    this.arena = arena; // config.worlds.drone
    this.tf = tf;
    this.root = new THREE.Group();
    this.root.matrixAutoUpdate = false;
    this.root.visible = false; // until the drone world says something
    this.frame = "map";
    this.present = false;
    this._sockets = [];
    this._pose = null;
    this._boxes = null;
    this._build();
  }

  _build() {
    const half = this.arena.fly_half_size_m;
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(2 * half, 2 * half), new THREE.MeshBasicMaterial({ color: COLORS.ground }));
    ground.position.z = -0.02; // under the grid, which lies at z = 0 of the fixed frame
    const outline = new THREE.LineLoop(
      new THREE.BufferGeometry().setFromPoints([
        new THREE.Vector3(-half, -half, 0),
        new THREE.Vector3(half, -half, 0),
        new THREE.Vector3(half, half, 0),
        new THREE.Vector3(-half, half, 0),
      ]),
      new THREE.LineDashedMaterial({ color: COLORS.arena, dashSize: 0.6, gapSize: 0.9 }),
    );
    outline.computeLineDistances();
    this.boxes = new THREE.Group();
    // The pose goes on this group; the model inside it is drawn at least MIN_MODEL_PX across
    // (fitModel): at its true size close up, larger when the whole arena is in view.
    this.drone = new THREE.Group();
    this.model = droneModel();
    this.drone.add(this.model);
    this.drone.matrixAutoUpdate = false;
    this.drone.visible = false;
    // A line from the drone down to the ground: height is hard to judge in a perspective view.
    this.dropLine = new THREE.Line(
      new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
      new THREE.LineDashedMaterial({ color: COLORS.drone, dashSize: 0.15, gapSize: 0.1 }),
    );
    this.dropLine.frustumCulled = false;
    this.dropLine.visible = false;
    this.root.add(ground, outline, this.boxes, this.drone, this.dropLine);
  }

  start() {
    // The drone world's names, from its description; read once someone publishes them (never in
    // another world).
    const open = (topic, rate, handler) =>
      this._sockets.push(new TopicSocket(topic, { rate, mode: "subscribe", onMessage: handler }).openWhenPublished());
    open(this.arena.topics.pose, 30, (msg) => {
      this._pose = msg;
    });
    open(this.arena.topics.boxes, 2, (msg) => {
      this._boxes = msg;
    });
  }

  /** Apply the newest pose and boxes; place the world in the fixed frame. Throws BadData. */
  update(ctx) {
    let changed = false;
    const messages = [this._pose, this._boxes].filter(Boolean);
    for (const msg of messages) {
      const frame = frameName(msg.header && msg.header.frame_id) || "map";
      this.tf.addFrame(frame);
      this.frame = frame;
      this.present = true;
    }
    const pose = this._pose;
    const boxes = this._boxes;
    this._pose = this._boxes = null;
    if (pose) {
      setPoseMatrix(this.drone.matrix, pose.pose, "/drone/pose pose");
      this.drone.matrixWorldNeedsUpdate = true;
      this.drone.visible = true;
      const { x, y, z } = pose.pose.position;
      this.dropLine.geometry.attributes.position.array.set([x, y, z, x, y, 0]);
      this.dropLine.geometry.attributes.position.needsUpdate = true;
      this.dropLine.computeLineDistances();
      this.dropLine.visible = z > 0.2;
      changed = true;
    }
    if (boxes) {
      this._setBoxes(boxes.poses);
      changed = true;
    }
    return changed;
  }

  _setBoxes(poses) {
    if (!Array.isArray(poses)) throw new BadData("/simulator/boxes poses is not a list");
    const matrices = poses.map((p, i) => setPoseMatrix(new THREE.Matrix4(), p, `/simulator/boxes poses[${i}]`));
    const size = this.arena.box_size_m;
    while (this.boxes.children.length > matrices.length) {
      const old = this.boxes.children[this.boxes.children.length - 1];
      old.removeFromParent();
      disposeObject(old);
    }
    while (this.boxes.children.length < matrices.length) {
      const box = new THREE.Mesh(unitGeometry().box, solidMaterial(COLORS.box));
      box.add(new THREE.LineSegments(new THREE.EdgesGeometry(unitGeometry().box), new THREE.LineBasicMaterial({ color: COLORS.boxEdge })));
      box.matrixAutoUpdate = false;
      this.boxes.add(box);
    }
    matrices.forEach((matrix, i) => {
      const box = this.boxes.children[i];
      box.matrix.copy(matrix).scale(new THREE.Vector3(size, size, size));
      box.matrixWorldNeedsUpdate = true;
    });
  }

  /** Where the drone is, in the fixed frame (for the follow view), or null. */
  followPoint() {
    if (!this.drone.visible || !this.root.visible) return null;
    this.root.updateMatrixWorld(true);
    return new THREE.Vector3().setFromMatrixPosition(this.drone.matrixWorld);
  }

  extent() {
    return this.arena.fly_half_size_m;
  }

  /** What the view frames at open: the arena the boxes lie in, up to above a flying drone. */
  bounds() {
    const half = this.arena.arena_half_size_m;
    return new THREE.Box3(new THREE.Vector3(-half, -half, 0), new THREE.Vector3(half, half, ARENA_HEIGHT_M));
  }

  followDistance() {
    return FOLLOW_DISTANCE_M;
  }

  /** Scale the model so that it is at least `minPx` across where it is; true if that changed. */
  fitModel(pixelsPerMetre, minPx) {
    if (!this.drone.visible) return false;
    this.root.updateMatrixWorld(true);
    const at = new THREE.Vector3().setFromMatrixPosition(this.drone.matrixWorld);
    const changed = fitScale(this.model, Math.max(1, minPx / (DRONE_SPAN_M * pixelsPerMetre(at))), [1, 1, 1]);
    this.model.position.z = (this.model.scale.z - 1) * SKID_DEPTH_M; // grown from its skids: never into the ground
    return changed;
  }

  snapshot() {
    this.root.updateMatrixWorld(true);
    const at = (object) => new THREE.Vector3().setFromMatrixPosition(object.matrixWorld).toArray().map((v) => Math.round(v * 1000) / 1000);
    return {
      present: this.present,
      frame: this.frame,
      drone: this.drone.visible ? at(this.drone) : null,
      droneScale: Math.round(this.model.scale.x * 1000) / 1000, // drawn size / true size
      boxes: this.boxes.children.map(at),
    };
  }

  stop() {
    for (const socket of this._sockets) socket.close();
    this._sockets = [];
  }
}
