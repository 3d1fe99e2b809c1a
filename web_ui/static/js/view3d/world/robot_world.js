// The robot world in 3D: the room's walls and boxes (the simulator's /simulator/obstacles, a
// MarkerArray drawn by the markers display's own code), the walking person of /simulator/people,
// and a Neato-sized robot at every `base_link` (`robot1/base_link`, ...) with its laser at the
// matching `base_laser_link`, wherever the TF tree puts them: like rviz's RobotModel, the robot
// is drawn where TF (odometry) says it is, so the scan lines up with it.

import * as THREE from "three";
import { TopicSocket } from "../../api.js";
import { MarkerDisplay } from "../displays/markers.js";
import { BadData, frameName, setPoseMatrix } from "../ros_math.js";
import { disposeObject, fitScale, solidMaterial, unitGeometry } from "../shapes.js";

const COLORS = { robot: 0x61afef, front: 0xffb74d, laser: 0x2b2f36, person: 0xe5c07b };
const ROBOT_HEIGHT_M = 0.09;
const PERSON_HEIGHT_M = 1.7; // what is drawn above the legs the laser sees: a person, to scale
const BASE = /(^|\/)base_link$/;

const FOLLOW_DISTANCE_M = 2.2; // Follow brings the camera this close: the robot about 65 px across
const WALL_HEIGHT_M = 0.5; // framed above the floor: the walls and the person's legs

/** A round robot as a Neato seen from above: its body, a bumper ring round the front half, and
 * an arrow on top pointing where it drives (+x). */
function robotModel(radius) {
  const group = new THREE.Group();
  const { cylinder } = unitGeometry();
  const body = new THREE.Mesh(cylinder, solidMaterial(COLORS.robot));
  body.scale.set(2 * radius, 2 * radius, ROBOT_HEIGHT_M);
  body.position.z = ROBOT_HEIGHT_M / 2;
  const bumper = new THREE.Mesh(
    new THREE.CylinderGeometry(radius + 0.012, radius + 0.012, ROBOT_HEIGHT_M * 0.5, 24, 1, true, Math.PI / 2, Math.PI).rotateX(Math.PI / 2),
    solidMaterial(0x2b2f36),
  );
  bumper.material.side = THREE.DoubleSide;
  bumper.position.z = ROBOT_HEIGHT_M * 0.35;
  const arrow = new THREE.Mesh(
    new THREE.ShapeGeometry(
      new THREE.Shape([
        new THREE.Vector2(radius * 0.85, 0), // clear of the laser turret in the middle
        new THREE.Vector2(radius * 0.3, radius * 0.42),
        new THREE.Vector2(radius * 0.3, -radius * 0.42),
      ]),
    ),
    solidMaterial(COLORS.front),
  );
  arrow.position.z = ROBOT_HEIGHT_M + 0.002;
  group.add(body, bumper, arrow);
  return group;
}

function laserModel() {
  const laser = new THREE.Mesh(unitGeometry().cylinder, solidMaterial(COLORS.laser));
  laser.scale.set(0.07, 0.07, 0.04);
  return new THREE.Group().add(laser); // the group takes the frame's matrix, the mesh keeps its size
}

/** Two legs (what the scan sees), a body and a head, facing +x of the pose. */
function personModel(legRadius, legSpacing) {
  const group = new THREE.Group();
  const { cylinder, sphere, box } = unitGeometry();
  const material = solidMaterial(COLORS.person);
  const legHeight = PERSON_HEIGHT_M * 0.47;
  for (const side of [1, -1]) {
    const leg = new THREE.Mesh(cylinder, material);
    leg.scale.set(2 * legRadius, 2 * legRadius, legHeight);
    leg.position.set(0, (side * legSpacing) / 2, legHeight / 2);
    group.add(leg);
  }
  const body = new THREE.Mesh(box, material);
  body.scale.set(0.25, legSpacing + 2 * legRadius, PERSON_HEIGHT_M * 0.38);
  body.position.z = legHeight + (PERSON_HEIGHT_M * 0.38) / 2;
  const head = new THREE.Mesh(sphere, material);
  head.scale.setScalar(PERSON_HEIGHT_M * 0.13);
  head.position.z = PERSON_HEIGHT_M * 0.93;
  group.add(body, head);
  return group;
}

export class RobotWorld {
  /** `room`: config.worlds.robot, the room's sizes as the core serves them (never spelled here). */
  constructor(room, tf, env) {
    this.room = room;
    this.tf = tf;
    this.root = new THREE.Group();
    this.obstacles = new MarkerDisplay(room.topics.obstacles, "visualization_msgs/msg/MarkerArray", {}, env);
    this.root.add(this.obstacles.root);
    this.people = new THREE.Group();
    this.root.add(this.people);
    this.robots = new Map(); // base frame -> {body, laser, laserFrame}
    this._peopleMsg = null;
    this._peopleFrame = "map";
    this._socket = null;
  }

  get present() {
    return this.robots.size > 0 || this.obstacles.objects.size > 0;
  }

  start() {
    this.obstacles.start();
    this._socket = new TopicSocket(this.room.topics.people, {
      rate: 10,
      mode: "subscribe",
      onMessage: (msg) => {
        this._peopleMsg = msg;
      },
    }).openWhenPublished(); // the robot world's: never read in another
  }

  stop() {
    this.obstacles.stop();
    this._socket?.close();
  }

  /** Follow the robots' frames; apply the newest people; the room as its markers. Throws BadData. */
  update(ctx) {
    let changed = this.obstacles.update(ctx);
    if (this._peopleMsg) {
      this._setPeople(this._peopleMsg);
      this._peopleMsg = null;
      changed = true;
    }
    if (this.people.children.length && (changed || ctx.tfChanged || ctx.fixedFrameChanged)) {
      const found = ctx.lookup(this._peopleFrame, null, this.people.matrix);
      this.people.visible = !found.error;
      this.people.matrixAutoUpdate = false;
      this.people.matrixWorldNeedsUpdate = true;
    }
    if (ctx.tfChanged || ctx.fixedFrameChanged || ctx.tfStructureChanged) {
      this._placeRobots(ctx);
      changed = true;
    }
    return changed;
  }

  _setPeople(msg) {
    if (!Array.isArray(msg.poses)) throw new BadData("/simulator/people poses is not a list");
    const matrices = msg.poses.map((p, i) => setPoseMatrix(new THREE.Matrix4(), p, `/simulator/people poses[${i}]`));
    this._peopleFrame = frameName(msg.header && msg.header.frame_id) || "map";
    this.tf.addFrame(this._peopleFrame);
    while (this.people.children.length > matrices.length) {
      const gone = this.people.children[this.people.children.length - 1];
      gone.removeFromParent();
      disposeObject(gone);
    }
    while (this.people.children.length < matrices.length) {
      const person = personModel(this.room.leg_radius_m, this.room.leg_spacing_m);
      person.matrixAutoUpdate = false;
      this.people.add(person);
    }
    matrices.forEach((matrix, i) => {
      this.people.children[i].matrix.copy(matrix);
      this.people.children[i].matrixWorldNeedsUpdate = true;
    });
  }

  _placeRobots(ctx) {
    for (const frame of this.tf.frames()) {
      if (BASE.test(frame) && !this.robots.has(frame)) {
        // The pose goes on `body`; the model inside is drawn at least MIN_MODEL_PX across
        // (fitModels), wider only: its height and the laser on top stay as they are.
        const model = robotModel(this.room.robot_radius_m);
        const robot = {
          body: new THREE.Group().add(model),
          model,
          laser: laserModel(),
          laserFrame: frame.replace(BASE, "$1base_laser_link"),
        };
        for (const part of [robot.body, robot.laser]) {
          part.matrixAutoUpdate = false;
          this.root.add(part);
        }
        this.robots.set(frame, robot);
      }
    }
    for (const [frame, robot] of this.robots) {
      const body = ctx.lookup(frame, null, robot.body.matrix);
      robot.body.visible = !body.error;
      const laser = this.tf.has(robot.laserFrame) ? ctx.lookup(robot.laserFrame, null, robot.laser.matrix) : { error: "absent" };
      robot.laser.visible = !laser.error;
      robot.body.matrixWorldNeedsUpdate = robot.laser.matrixWorldNeedsUpdate = true;
    }
  }

  /** The first robot in the fixed frame (the follow view), or null. */
  followPoint() {
    for (const robot of this.robots.values()) {
      if (robot.body.visible) return new THREE.Vector3().setFromMatrixPosition(robot.body.matrix);
    }
    return null;
  }

  extent() {
    return this.room.room_half_size_m + 1;
  }

  /** What the view frames at open: the room, walls included. */
  bounds() {
    const half = this.room.room_half_size_m + this.room.wall_thickness_m;
    return new THREE.Box3(new THREE.Vector3(-half, -half, 0), new THREE.Vector3(half, half, WALL_HEIGHT_M));
  }

  followDistance() {
    return FOLLOW_DISTANCE_M;
  }

  /** Widen each robot's model to at least `minPx` across where it is; true if any changed. */
  fitModels(pixelsPerMetre, minPx) {
    let changed = false;
    for (const robot of this.robots.values()) {
      if (!robot.body.visible) continue;
      const at = new THREE.Vector3().setFromMatrixPosition(robot.body.matrix);
      const factor = Math.max(1, minPx / (2 * this.room.robot_radius_m * pixelsPerMetre(at)));
      changed = fitScale(robot.model, factor, [1, 1, 0]) || changed;
    }
    return changed;
  }

  status() {
    return this.obstacles.status();
  }

  snapshot() {
    const at = (object) => new THREE.Vector3().setFromMatrixPosition(object.matrix).toArray().map((v) => Math.round(v * 1000) / 1000);
    const robots = [...this.robots].map(([frame, r]) => ({
      frame,
      position: r.body.visible ? at(r.body) : null,
      scale: Math.round(r.model.scale.x * 1000) / 1000, // drawn width / true width
      laser: r.laser.visible ? at(r.laser) : null,
    }));
    const first = robots.find((r) => r.position) || null;
    this.root.updateMatrixWorld(true);
    return {
      present: this.present,
      robot: first ? first.position : null,
      laser: first ? first.laser : null,
      robots,
      obstacles: this.obstacles.drawn().markers.map((m) => ({ ns: m.ns, id: m.id, position: m.position })),
      people: this.people.visible ? this.people.children.map((p) => new THREE.Vector3().setFromMatrixPosition(p.matrixWorld).toArray()) : [],
    };
  }
}
