// Connection status: the header pill and the banner that says what is wrong and what to do
// (core unreachable, simulator absent or not publishing: /drone/pose, or the robot's /odom).

import { ROBOT_TOPICS, topicIn } from "./room.js";
import { DRONE_TOPICS } from "./world.js";

const STALE_POSE_S = 2;
const STARTUP_GRACE_MS = 3000; // sockets are still connecting: no "not publishing" yet

export class StatusBanner {
  constructor({ banner, pill, summary, graph, world, room }) {
    this.banner = banner;
    this.pill = pill;
    this.summary = summary;
    this.graph = graph;
    this.world = world;
    this.room = room;
    this.message = "";
  }

  start() {
    this.graph.addEventListener("update", () => this.update());
    setInterval(() => this.update(), 500);
    this.update();
  }

  update() {
    const { graph, world } = this;
    let state = "ok";
    let message = "";
    if (graph.error) {
      state = "error";
      message = `Core unreachable at ${location.origin} (${graph.error.message}); retrying… Is \`skydeck core\` (or \`make up\`) running?`;
      this._pill("error", "core unreachable");
    } else if (!graph.graph) {
      this._pill("connecting", "connecting…");
    } else {
      const nodes = graph.graph.nodes.length;
      this._pill("ok", `core ok · ${nodes} node${nodes === 1 ? "" : "s"}`);
      const robot = world.kind === "robot" && this.room.robots.length > 0;
      const name = robot ? topicIn(this.room.robots[0].namespace, ROBOT_TOPICS.odom) : DRONE_TOPICS.pose;
      const pose = graph.graph.topics.find((t) => t.name === name);
      const age = robot ? this.room.odomAgeSeconds() : world.poseAgeSeconds();
      if (!pose || !pose.publishers.length) {
        state = "warn";
        message = `Simulator not running: nothing publishes ${name}. Start it with \`skydeck run sim\` (or \`make up\`; \`make robot\` for the robot world).`;
      } else if (age > STALE_POSE_S && !(age === Infinity && performance.now() < STARTUP_GRACE_MS)) {
        state = "warn";
        message = Number.isFinite(age)
          ? `Simulator not publishing: no ${name} for ${age.toFixed(0)} s (${pose.publishers.join(", ")} registered).`
          : `Simulator not publishing: no ${name} received yet from ${pose.publishers.join(", ")}.`;
      }
    }
    this._banner(state, message);
    this._summary();
  }

  _pill(state, text) {
    this.pill.dataset.state = state;
    this.pill.textContent = text;
  }

  _banner(state, message) {
    this.banner.dataset.state = state;
    this.banner.hidden = state === "ok";
    if (message !== this.message) {
      this.banner.textContent = message;
      this.message = message;
    }
  }

  _summary() {
    if (this.world.kind === "robot") {
      this._robotSummary();
      return;
    }
    const { pose, controlState, droneState } = this.world;
    if (!pose) {
      this.summary.textContent = "no pose yet";
      return;
    }
    const heading = ((pose.yaw * 180) / Math.PI).toFixed(0);
    const parts = [`x ${pose.x.toFixed(2)}  y ${pose.y.toFixed(2)}  z ${pose.z.toFixed(2)} m  yaw ${heading}°`];
    if (controlState) parts.push(`control: ${controlState.state}`);
    if (droneState && droneState.mode) parts.push(`mode: ${droneState.mode}`);
    this.summary.textContent = parts.join("  ·  ");
  }

  _robotSummary() {
    const robot = this.room.robots[0];
    if (!robot || !robot.pose) {
      this.summary.textContent = "no robot pose yet";
      return;
    }
    const { pose, odom } = robot;
    const heading = ((pose.yaw * 180) / Math.PI).toFixed(0);
    const parts = [`${robot.label}: x ${pose.x.toFixed(2)}  y ${pose.y.toFixed(2)} m  yaw ${heading}°`];
    if (odom) parts.push(`odom: ${odom.v.toFixed(2)} m/s  ${odom.w.toFixed(2)} rad/s`);
    this.summary.textContent = parts.join("  ·  ");
  }
}
