// The workshop system as the dashboard knows it: which world the simulator runs (from the latched
// /simulator/world), and for the drone world the latest pose, its track and history, the boxes,
// the AI's status and control's state, fed by topic sockets through the core. The robot world's
// state lives in room.js. The drone world's names come from its description (GET /api/config's
// worlds.drone.topics) and are read only while no other world runs and once someone publishes
// each: the dashboard never subscribes to another world's names, nor creates a topic.

import { TopicSocket } from "./api.js";
import { config } from "./config.js";
import { isFiniteNumber, stampSeconds, yawOf } from "./geometry.js";

/** The drone world's topics by role ({pose: "/drone/pose", ...}), as the core describes them. */
export const DRONE_TOPICS = (config.worlds.drone && config.worlds.drone.topics) || {};
const WORLD_TOPIC = "/simulator/world"; // every world's (the simulator's floor)

const TRACK_MAX_POINTS = 3000;
const TRACK_MIN_STEP_M = 0.05;
const HISTORY_WINDOW_S = 60;
const HISTORY_PERIOD_S = 0.1;
const JUMP_RESET_M = 5; // a pose this far from the last one is a reset: start a new track

export class World extends EventTarget {
  constructor() {
    super();
    this.pose = null; // {x, y, z, yaw, frame, stamp, receivedAt}
    this.track = []; // [{x, y}]
    this.history = []; // [{t, z, speed}] (t: performance.now() / 1000), last 60 s
    this.simBoxes = []; // [{x, y, yaw}] from /simulator/boxes
    this.perceptionBoxes = []; // [{x, y, z}] from /perception/boxes (the AI's indices)
    this.aiStatus = null;
    this.controlState = null;
    this.droneState = null;
    this.flyTarget = null; // the last clicked target {x, y}
    this.kind = null; // "drone" | "robot" (a world's name, or the world's it extends) once /simulator/world has said; null before
    this.namespaces = []; // the robot world's robots: ["/"] or ["/robot1", "/robot2", ...]
    this._speedRef = null; // an earlier pose to differentiate against
    this._worldSocket = null;
    this._droneSockets = [];
  }

  /** Read /simulator/world, and the drone world's topics until it names another world: the
   * default world (a recording played with no simulator shows too). Each is read once someone
   * publishes it, so another world's names never are. */
  start() {
    this._worldSocket = new TopicSocket(WORLD_TOPIC, { queue: 2, onMessage: (msg) => this._onWorld(msg) }).openWhenPublished();
    this._startDrone();
  }

  _startDrone() {
    if (this._droneSockets.length) return;
    const sub = (role, options, handler) => {
      const name = DRONE_TOPICS[role];
      if (!name) return;
      const socket = new TopicSocket(name, { ...options, onMessage: handler });
      this._droneSockets.push(socket);
      socket.openWhenPublished();
    };
    sub("pose", { rate: 30 }, (msg) => this._onPose(msg));
    sub("boxes", { rate: 2 }, (msg) => {
      this.simBoxes = (msg.poses || []).map((p) => ({ x: p.position.x, y: p.position.y, yaw: yawOf(p.orientation) }));
    });
    sub("perception_boxes", { rate: 2 }, (msg) => {
      this.perceptionBoxes = (msg.points || []).map((p) => ({ x: p.x, y: p.y, z: p.z }));
    });
    sub("ai_status", { queue: 10 }, (msg) => {
      this.aiStatus = msg;
      this._emit("ai-status");
    });
    sub("control_state", { rate: 10 }, (msg) => {
      this.controlState = msg;
    });
    sub("state", { rate: 2 }, (msg) => {
      this.droneState = msg;
    });
  }

  _stopDrone() {
    for (const socket of this._droneSockets) socket.close();
    this._droneSockets = [];
  }

  /** Seconds since the last /drone/pose frame, or Infinity when none came yet. */
  poseAgeSeconds() {
    if (!this.pose) return Infinity;
    return (performance.now() - this.pose.receivedAt) / 1000;
  }

  clearTrack() {
    this.track = [];
  }

  _onWorld(msg) {
    const named = typeof msg.world === "string" && msg.world ? msg.world : "drone";
    // A world built on another (the soccer room on the robot world) is shown as that one.
    const kind = (config.worlds[named] && config.worlds[named].extends) || named;
    const namespaces = Array.isArray(msg.namespaces) ? msg.namespaces.filter((ns) => typeof ns === "string") : [];
    if (kind === this.kind && namespaces.join() === this.namespaces.join()) return;
    this.kind = kind;
    this.namespaces = namespaces;
    if (kind === "drone") this._startDrone();
    else this._stopDrone();
    this._emit("world");
  }

  _onPose(msg) {
    const position = msg.pose && msg.pose.position;
    if (!position || !isFiniteNumber(position.x) || !isFiniteNumber(position.y) || !isFiniteNumber(position.z)) return;
    const now = performance.now();
    const pose = {
      x: position.x,
      y: position.y,
      z: position.z,
      yaw: yawOf(msg.pose.orientation),
      frame: msg.header ? msg.header.frame_id : "",
      stamp: stampSeconds(msg.header && msg.header.stamp),
      receivedAt: now,
    };
    const last = this.track[this.track.length - 1];
    if (last && Math.hypot(pose.x - last.x, pose.y - last.y) > JUMP_RESET_M) {
      this.track = [];
      this._speedRef = null;
    }
    if (!last || Math.hypot(pose.x - last.x, pose.y - last.y) >= TRACK_MIN_STEP_M) {
      this.track.push({ x: pose.x, y: pose.y });
      if (this.track.length > TRACK_MAX_POINTS) this.track.splice(0, this.track.length - TRACK_MAX_POINTS);
    }
    this.pose = pose;
    this._sample(pose, now / 1000);
    this._emit("pose");
  }

  // Altitude and horizontal speed every 0.1 s; speed over >= 0.1 s of motion, by the message
  // stamps when they advance (sim time, right at any --speed) and the arrival time otherwise.
  _sample(pose, t) {
    const ref = this._speedRef;
    const last = this.history[this.history.length - 1];
    if (last && t - last.t < HISTORY_PERIOD_S) return;
    let speed = last ? last.speed : 0;
    if (ref) {
      const dt = pose.stamp !== null && ref.stamp !== null && pose.stamp > ref.stamp ? pose.stamp - ref.stamp : t - ref.t;
      if (dt > 0) speed = Math.hypot(pose.x - ref.x, pose.y - ref.y) / dt;
    }
    this._speedRef = { x: pose.x, y: pose.y, stamp: pose.stamp, t };
    this.history.push({ t, z: pose.z, speed });
    while (this.history.length && t - this.history[0].t > HISTORY_WINDOW_S) this.history.shift();
  }

  _emit(type) {
    this.dispatchEvent(new Event(type));
  }
}
