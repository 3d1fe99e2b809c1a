// The class page's 3D scene: the room (its walls and boxes from /simulator/obstacles) and every
// student's robot where the simulator says it is (/simulator/robots, in the order of
// /simulator/world's namespaces), named, the selected student's robot in the accent colour.

import * as THREE from "three";
import { TopicSocket } from "./api.js";
import { Scene3D } from "./view3d/scene.js";
import { disposeObject, setSpriteText, solidMaterial, textSprite, unitGeometry } from "./view3d/shapes.js";

const ROBOT_RADIUS_M = 0.165;
const ROBOT_HEIGHT_M = 0.09;
const COLORS = { robot: 0x8594a3, selected: 0x61afef, front: 0xffb74d, wall: 0xeaeaf2, box: 0x8c6b4d };
const TRUTH_RATE_HZ = 10; // the simulator's own rate for the truth: nothing is dropped

function robotModel() {
  const group = new THREE.Group();
  const body = new THREE.Mesh(unitGeometry().cylinder, solidMaterial(COLORS.robot));
  body.scale.set(2 * ROBOT_RADIUS_M, 2 * ROBOT_RADIUS_M, ROBOT_HEIGHT_M);
  body.position.z = ROBOT_HEIGHT_M / 2;
  const nose = new THREE.Mesh(unitGeometry().box, solidMaterial(COLORS.front));
  nose.scale.set(0.08, 0.05, 0.02);
  nose.position.set(ROBOT_RADIUS_M * 0.6, 0, ROBOT_HEIGHT_M + 0.01);
  const label = textSprite("", "#ffffff", 0.22);
  label.position.z = 0.42;
  group.add(body, nose, label);
  group.userData = { body, label };
  return group;
}

export class ClassScene {
  constructor(canvas) {
    this.view = new Scene3D(canvas, { onTick: () => false });
    this.view.topDown(new THREE.Vector3(0, 0, 0), 13);
    this.names = []; // the students, in the world's order
    this.poses = [];
    this.robots = [];
    this.selected = null;
    this.room = new THREE.Group();
    this.view.add(this.room);
    this.messages = 0;
    this.sockets = [
      new TopicSocket("/simulator/world", { onMessage: (m) => this._world(m) }),
      new TopicSocket("/simulator/robots", { rate: TRUTH_RATE_HZ, queue: 1, onMessage: (m) => this._robots(m) }),
      new TopicSocket("/simulator/obstacles", { onMessage: (m) => this._obstacles(m) }),
    ];
  }

  setShown(shown) {
    this.view.setShown(shown);
    for (const socket of this.sockets) (shown ? socket.openWhenPublished() : socket.close());
  }

  setSelected(name) {
    this.selected = name;
    this._paint();
  }

  _world(msg) {
    const names = (msg.namespaces || []).map((ns) => (ns === "/" ? "robot" : ns.slice(1)));
    if (names.join() === this.names.join()) return;
    this.names = names;
    this._paint();
  }

  _robots(msg) {
    this.messages += 1;
    this.poses = msg.poses || [];
    while (this.robots.length < this.poses.length) {
      const robot = robotModel();
      this.robots.push(robot);
      this.view.add(robot);
    }
    this.poses.forEach((pose, i) => {
      const robot = this.robots[i];
      const q = pose.orientation;
      robot.position.set(pose.position.x, pose.position.y, 0);
      robot.rotation.set(0, 0, 2 * Math.atan2(q.z, q.w));
      robot.visible = true;
    });
    for (const extra of this.robots.slice(this.poses.length)) extra.visible = false;
    this._paint();
  }

  _paint() {
    this.robots.forEach((robot, i) => {
      const name = this.names[i] || `robot ${i + 1}`;
      const selected = name === this.selected;
      robot.userData.body.material.color.setHex(selected ? COLORS.selected : COLORS.robot);
      setSpriteText(robot.userData.label, name, selected ? "#61afef" : "#ffffff", 0.22);
    });
    this.view.invalidate();
  }

  _obstacles(msg) {
    for (const child of [...this.room.children]) {
      this.room.remove(child);
      disposeObject(child);
    }
    for (const marker of msg.markers || []) {
      if (marker.type !== 1) continue; // CUBE: the walls and boxes
      const cube = new THREE.Mesh(unitGeometry().box, solidMaterial(marker.ns === "walls" ? COLORS.wall : COLORS.box));
      const { position: p, orientation: q } = marker.pose;
      cube.position.set(p.x, p.y, p.z);
      cube.quaternion.set(q.x, q.y, q.z, q.w);
      cube.scale.set(marker.scale.x, marker.scale.y, marker.scale.z);
      this.room.add(cube);
    }
    this.view.invalidate();
  }

  snapshot() {
    return {
      messages: this.messages,
      robots: this.poses.map((pose, i) => ({
        name: this.names[i] || null,
        x: pose.position.x,
        y: pose.position.y,
        selected: this.names[i] === this.selected,
      })),
      roomParts: this.room.children.length,
    };
  }
}
