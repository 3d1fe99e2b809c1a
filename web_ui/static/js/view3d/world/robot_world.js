// The robot world in 3D: a Neato-sized robot at `base_link` and its laser at `base_laser_link`,
// wherever the TF tree puts them, so any robot that publishes those frames is drawn.

import * as THREE from "three";
import { solidMaterial, unitGeometry } from "../shapes.js";

const ROBOT_DIAMETER_M = 0.33;
const ROBOT_HEIGHT_M = 0.09;
const COLORS = { robot: 0x61afef, front: 0xffb74d, laser: 0x2b2f36 };

/** A round robot 0.33 m across, its front marked by a wedge along +x. */
function robotModel() {
  const group = new THREE.Group();
  const { cylinder, box } = unitGeometry();
  const body = new THREE.Mesh(cylinder, solidMaterial(COLORS.robot));
  body.scale.set(ROBOT_DIAMETER_M, ROBOT_DIAMETER_M, ROBOT_HEIGHT_M);
  body.position.z = ROBOT_HEIGHT_M / 2;
  const front = new THREE.Mesh(box, solidMaterial(COLORS.front));
  front.scale.set(0.1, 0.04, 0.02);
  front.position.set(ROBOT_DIAMETER_M / 2 - 0.06, 0, ROBOT_HEIGHT_M + 0.01);
  group.add(body, front);
  return group;
}

function laserModel() {
  const laser = new THREE.Mesh(unitGeometry().cylinder, solidMaterial(COLORS.laser));
  laser.scale.set(0.07, 0.07, 0.04);
  return new THREE.Group().add(laser); // the group takes the frame's matrix, the mesh keeps its size
}

export class RobotWorld {
  constructor(tf) {
    this.tf = tf;
    this.root = new THREE.Group();
    this.robot = robotModel();
    this.laser = laserModel();
    for (const part of [this.robot, this.laser]) {
      part.matrixAutoUpdate = false;
      part.visible = false;
      this.root.add(part);
    }
    this.present = false;
  }

  start() {}

  stop() {}

  /** Follow base_link and base_laser_link in the fixed frame; frames not there hide their part. */
  update(ctx) {
    if (!(ctx.tfChanged || ctx.fixedFrameChanged || ctx.tfStructureChanged)) return false;
    for (const [part, frame] of [[this.robot, "base_link"], [this.laser, "base_laser_link"]]) {
      const found = this.tf.has(frame) ? ctx.lookup(frame, null, part.matrix) : { error: "absent" };
      part.visible = !found.error;
      part.matrixWorldNeedsUpdate = true;
    }
    this.present = this.tf.has("base_link");
    return true;
  }

  followPoint() {
    if (!this.robot.visible) return null;
    return new THREE.Vector3().setFromMatrixPosition(this.robot.matrix);
  }

  extent() {
    return 5;
  }

  snapshot() {
    const at = (object) => new THREE.Vector3().setFromMatrixPosition(object.matrix).toArray().map((v) => Math.round(v * 1000) / 1000);
    return { present: this.present, robot: this.robot.visible ? at(this.robot) : null, laser: this.laser.visible ? at(this.laser) : null };
  }
}
