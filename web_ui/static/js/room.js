// The robot world as the dashboard knows it: the room's obstacles, the walking person, and per
// robot its true pose, odometry (and trail), latest scan and bumper, fed by topic sockets through
// the core. Started once /simulator/world says the robot world runs (see world.js); the names are
// the robot world's description's (GET /api/config's worlds.robot.topics), each read once
// someone publishes it.

import { TopicSocket } from "./api.js";
import { config } from "./config.js";
import { isFiniteNumber, stampSeconds, yawOf } from "./geometry.js";

/** The robot world's topics by role; relative ones ("odom") live in each robot's namespace. */
export const ROBOT_TOPICS = (config.worlds.robot && config.worlds.robot.topics) || {};

const TRAIL_MAX_POINTS = 3000;
const TRAIL_MIN_STEP_M = 0.02;
const JUMP_RESET_M = 1; // odometry this far from the last point: a reset, start a new trail
const HISTORY_WINDOW_S = 60;
const HISTORY_PERIOD_S = 0.1;

/** The absolute name of topic `name` in a robot's namespace ("/" or "/robot1"). */
export function topicIn(namespace, name) {
  return namespace === "/" ? `/${name}` : `${namespace}/${name}`;
}

function poseOf(p) {
  return { x: p.position.x, y: p.position.y, yaw: yawOf(p.orientation) };
}

/** One robot: where it truly is, what its wheels and laser say. */
class RobotState {
  constructor(namespace, index) {
    this.namespace = namespace;
    this.index = index;
    this.label = namespace === "/" ? "robot" : namespace.slice(1);
    this.pose = null; // the truth, from /simulator/robots {x, y, yaw}
    this.odom = null; // {x, y, yaw, v, w, frame, stamp, receivedAt} in its odom frame
    this.trail = []; // odometry, in its odom frame [{x, y}]
    this.scan = null; // {points: [{x, y}] in the laser frame, frame, stamp, receivedAt}
    this.bump = null; // the Bump message
  }
}

export class Room extends EventTarget {
  constructor() {
    super();
    this.robots = [];
    this.obstacles = []; // [{x, y, yaw, sx, sy}] boxes from /simulator/obstacles (ns "obstacles")
    this.people = []; // [{x, y, yaw}]
    this.odomFrames = new Map(); // odom frame -> its pose in map {x, y, yaw}, from /tf_static
    this.history = []; // [{t, speed, turn}] of the first robot, last 60 s
    this._sockets = [];
    this._robotSockets = [];
  }

  /** Subscribe to the room's topics and to each robot's (namespaces from /simulator/world). */
  start(namespaces) {
    if (!this._sockets.length) {
      this._sub(this._sockets, ROBOT_TOPICS.obstacles, { queue: 2 }, (msg) => this._onObstacles(msg));
      this._sub(this._sockets, ROBOT_TOPICS.people, { rate: 10 }, (msg) => {
        this.people = (msg.poses || []).map(poseOf);
      });
      this._sub(this._sockets, ROBOT_TOPICS.robots, { rate: 20 }, (msg) => {
        (msg.poses || []).forEach((p, i) => {
          if (this.robots[i]) this.robots[i].pose = poseOf(p);
        });
      });
      this._sub(this._sockets, ROBOT_TOPICS.tf_static, { queue: 4 }, (msg) => this._onStatic(msg));
    }
    for (const socket of this._robotSockets) socket.close();
    this._robotSockets = [];
    this.robots = namespaces.map((ns, i) => new RobotState(ns, i));
    const own = (robot, role) => ROBOT_TOPICS[role] && topicIn(robot.namespace, ROBOT_TOPICS[role]);
    for (const robot of this.robots) {
      this._sub(this._robotSockets, own(robot, "odom"), { rate: 20 }, (msg) => this._onOdom(robot, msg));
      this._sub(this._robotSockets, own(robot, "scan"), { rate: 5 }, (msg) => this._onScan(robot, msg));
      this._sub(this._robotSockets, own(robot, "bump"), { rate: 10 }, (msg) => {
        robot.bump = msg;
      });
    }
  }

  /** Close every socket (the simulator changed to the drone world). */
  stop() {
    for (const socket of [...this._sockets, ...this._robotSockets]) socket.close();
    this._sockets = [];
    this._robotSockets = [];
    this.robots = [];
  }

  clearTrails() {
    for (const robot of this.robots) robot.trail = [];
  }

  /** Seconds since the first robot's last /odom, or Infinity. */
  odomAgeSeconds() {
    const robot = this.robots[0];
    if (!robot || !robot.odom) return Infinity;
    return (performance.now() - robot.odom.receivedAt) / 1000;
  }

  /** A point of robot `robot`'s odom frame, in the map (through /tf_static's map -> odom). */
  odomToMap(robot, point) {
    const frame = this.odomFrames.get(robot.odom ? robot.odom.frame : "") || { x: 0, y: 0, yaw: 0 };
    const c = Math.cos(frame.yaw);
    const s = Math.sin(frame.yaw);
    return { x: frame.x + c * point.x - s * point.y, y: frame.y + s * point.x + c * point.y, yaw: (point.yaw || 0) + frame.yaw };
  }

  _sub(list, topic, options, handler) {
    if (topic) list.push(new TopicSocket(topic, { ...options, onMessage: handler }).openWhenPublished());
  }

  _onObstacles(msg) {
    this.obstacles = (msg.markers || [])
      .filter((m) => m.ns === "obstacles" && m.pose && m.scale)
      .map((m) => ({ ...poseOf(m.pose), sx: m.scale.x, sy: m.scale.y }));
  }

  _onStatic(msg) {
    for (const t of msg.transforms || []) {
      if (t.header.frame_id === "map" && t.child_frame_id.endsWith("odom")) {
        const { translation, rotation } = t.transform;
        this.odomFrames.set(t.child_frame_id, { x: translation.x, y: translation.y, yaw: yawOf(rotation) });
      }
    }
  }

  _onOdom(robot, msg) {
    const position = msg.pose && msg.pose.pose && msg.pose.pose.position;
    if (!position || !isFiniteNumber(position.x) || !isFiniteNumber(position.y)) return;
    const now = performance.now();
    const twist = msg.twist.twist;
    robot.odom = {
      x: position.x,
      y: position.y,
      yaw: yawOf(msg.pose.pose.orientation),
      v: twist.linear.x,
      w: twist.angular.z,
      frame: msg.header.frame_id,
      stamp: stampSeconds(msg.header.stamp),
      receivedAt: now,
    };
    const last = robot.trail[robot.trail.length - 1];
    const step = last ? Math.hypot(position.x - last.x, position.y - last.y) : Infinity;
    if (step > JUMP_RESET_M && last) robot.trail = [];
    if (step >= TRAIL_MIN_STEP_M) {
      robot.trail.push({ x: position.x, y: position.y });
      if (robot.trail.length > TRAIL_MAX_POINTS) robot.trail.splice(0, robot.trail.length - TRAIL_MAX_POINTS);
    }
    if (robot.index === 0) this._sample(robot.odom, now / 1000);
    this.dispatchEvent(new Event("odom"));
  }

  _onScan(robot, msg) {
    const ranges = Array.isArray(msg.ranges) ? msg.ranges : [];
    const points = [];
    ranges.forEach((r, i) => {
      if (!isFiniteNumber(r) || r <= 0 || r < msg.range_min || r > msg.range_max) return; // 0.0: no return
      const a = msg.angle_min + i * msg.angle_increment;
      points.push({ x: r * Math.cos(a), y: r * Math.sin(a) });
    });
    robot.scan = { points, frame: msg.header.frame_id, stamp: stampSeconds(msg.header.stamp), receivedAt: performance.now() };
  }

  // Speed and turn rate every 0.1 s, for the plots.
  _sample(odom, t) {
    const last = this.history[this.history.length - 1];
    if (last && t - last.t < HISTORY_PERIOD_S) return;
    this.history.push({ t, speed: odom.v, turn: odom.w });
    while (this.history.length && t - this.history[0].t > HISTORY_WINDOW_S) this.history.shift();
  }
}
