// Teleop from the keyboard or the on-screen pad: publishes geometry_msgs/msg/Twist at 10 Hz
// while keys (or pad keys, pressed with the mouse or a finger) are held and one zero Twist on
// release, on /drone/cmd_vel (world frame) in the drone world and on a robot's cmd_vel (body
// frame) in the robot world. Off by default; keys typed into form fields never count.

import { TopicSocket } from "./api.js";
import { config } from "./config.js";

const TYPE = "geometry_msgs/msg/Twist";
const PERIOD_MS = 100;
const YAW_RATE = 1.0; // rad/s
const CLIMB_RATE = 1.0; // m/s
const ROBOT_TURN_RATE = 1.0; // rad/s
// The speed slider per world: the robot's top speed comes from the core, never a copy.
const SPEEDS = {
  drone: { min: 0.5, max: 8, step: 0.5, value: 2 },
  robot: { min: 0.05, max: config.worlds.robot.max_linear_speed, step: 0.05, value: 0.2 },
};
const NOTES = {
  drone: "On: WASD / arrows move (as on the map), R/F up/down, Q/E yaw, space stops; or hold the keys above. Typing in a field never drives.",
  robot: "On: W/S or ↑/↓ drive forward / back, A/D or ←/→ (and Q/E) turn; hold two for an arc; space stops; or hold the keys above. Typing in a field never drives.",
};

// Key -> action. Directions are the map's: up is +y, right is +x (cmd_vel is world frame).
const KEYS = {
  KeyW: "up", ArrowUp: "up",
  KeyS: "down", ArrowDown: "down",
  KeyA: "left", ArrowLeft: "left",
  KeyD: "right", ArrowRight: "right",
  KeyR: "rise", KeyF: "sink",
  KeyQ: "ccw", KeyE: "cw",
};

function isTyping(target) {
  if (!(target instanceof Element)) return false;
  return target.closest("input, textarea, select, [contenteditable=''], [contenteditable='true'], dialog") !== null;
}

export class Teleop {
  constructor({ toggle, speed, speedLabel, keysView, note, topicLabel }) {
    this.toggle = toggle;
    this.note = note;
    this.topicLabel = topicLabel;
    this.kind = "drone";
    this.topic = config.worlds.drone ? config.worlds.drone.topics.cmd_vel : "";
    this.speed = speed;
    this.speedLabel = speedLabel;
    this.keysView = keysView;
    this.enabled = false;
    this.held = new Set(); // actions currently held
    this.sent = 0;
    this.socket = null;
    this._timer = null;
    this._moving = false;
    toggle.addEventListener("click", () => this.setEnabled(!this.enabled));
    speed.addEventListener("input", () => {
      speedLabel.textContent = Number(speed.value).toFixed(this.kind === "robot" ? 2 : 1);
    });
    // The pad: each key of keysView is a button held down while pressed (pointer capture, so
    // sliding off it and letting go still releases it); its "stop" key stops, as space does.
    keysView.addEventListener("pointerdown", (event) => this._pad(event, true));
    keysView.addEventListener("pointerup", (event) => this._pad(event, false));
    keysView.addEventListener("pointercancel", (event) => this._pad(event, false));
    window.addEventListener("keydown", (event) => this._key(event, true));
    window.addEventListener("keyup", (event) => this._key(event, false));
    window.addEventListener("blur", () => this._releaseAll());
    document.addEventListener("visibilitychange", () => this._releaseAll());
  }

  /** Drive the drone world ("drone", /drone/cmd_vel) or a robot ("robot", its cmd_vel topic). */
  setTarget(kind, topic) {
    if (kind === this.kind && topic === this.topic) return;
    const enabled = this.enabled;
    this.setEnabled(false);
    if (kind !== this.kind) {
      Object.assign(this.speed, SPEEDS[kind]);
      this.speed.value = String(SPEEDS[kind].value);
      this.speedLabel.textContent = Number(this.speed.value).toFixed(2);
    }
    this.kind = kind;
    this.topic = topic;
    this.topicLabel.textContent = `publishes ${topic}`;
    this.setEnabled(enabled);
    this._showNote();
  }

  setEnabled(enabled) {
    if (enabled === this.enabled) return;
    if (!enabled) this._releaseAll();
    this.enabled = enabled;
    this.toggle.setAttribute("aria-pressed", String(enabled));
    this.toggle.textContent = enabled ? "Teleop ON" : "Teleop off";
    this.keysView.classList.toggle("dim", !enabled);
    this._showNote();
    if (enabled) {
      this.toggle.blur(); // so space and arrows reach the window, not the button
      this.socket = new TopicSocket(this.topic, { type: TYPE, mode: "publish" }).open();
    } else if (this.socket) {
      const socket = this.socket;
      this.socket = null;
      setTimeout(() => socket.close(), 300); // let the zero Twist leave first
    }
  }

  _showNote() {
    this.note.textContent = this.enabled
      ? NOTES[this.kind]
      : this.kind === "robot"
        ? "Off: keys do nothing. Without a command for 0.5 s the robot stops by itself."
        : "Off: keys do nothing. Control's setpoint stream, when active, wins over teleop.";
  }

  /** The Twist for the keys held now. */
  twist() {
    const v = Number(this.speed.value);
    const h = this.held;
    const axis = (plus, minus) => (h.has(plus) ? 1 : 0) - (h.has(minus) ? 1 : 0);
    if (this.kind === "robot") {
      // Body frame: up/down drive, left/right (and the yaw keys) turn; both held make an arc.
      const turn = Math.max(-1, Math.min(1, axis("left", "right") + axis("ccw", "cw")));
      return { linear: { x: axis("up", "down") * v, y: 0, z: 0 }, angular: { x: 0, y: 0, z: turn * ROBOT_TURN_RATE } };
    }
    return {
      linear: { x: axis("right", "left") * v, y: axis("up", "down") * v, z: axis("rise", "sink") * CLIMB_RATE },
      angular: { x: 0, y: 0, z: axis("ccw", "cw") * YAW_RATE },
    };
  }

  _key(event, down) {
    if (!this.enabled || event.ctrlKey || event.metaKey || event.altKey || isTyping(event.target)) return;
    if (event.code === "Space") {
      event.preventDefault();
      if (down) this._releaseAll();
      return;
    }
    const action = KEYS[event.code];
    if (!action) return;
    event.preventDefault();
    this._hold(action, down);
  }

  _pad(event, down) {
    const key = event.target instanceof Element ? event.target.closest("kbd[data-key]") : null;
    if (!this.enabled || !key || !this.keysView.contains(key)) return;
    if (down && event.button !== 0) return; // only the primary button (or a touch) presses a key
    event.preventDefault();
    if (key.dataset.key === "stop") {
      if (down) this._releaseAll();
      return;
    }
    if (down) key.setPointerCapture(event.pointerId);
    this._hold(key.dataset.key, down);
  }

  _hold(action, down) {
    if (down) this.held.add(action);
    else this.held.delete(action);
    this._showKeys();
    if (this.held.size && !this._timer) {
      this._publish();
      this._timer = setInterval(() => this._publish(), PERIOD_MS);
    } else if (!this.held.size) {
      this._stop();
    }
  }

  _publish() {
    if (this.socket && this.socket.publish(this.twist())) {
      this.sent += 1;
      this._moving = true;
    }
  }

  _stop() {
    clearInterval(this._timer);
    this._timer = null;
    if (this._moving && this.socket) {
      this.socket.publish(this.twist()); // all zero now: one stop message
      this.sent += 1;
    }
    this._moving = false;
  }

  _releaseAll() {
    this.held.clear();
    this._showKeys();
    this._stop();
  }

  _showKeys() {
    for (const kbd of this.keysView.querySelectorAll("kbd")) {
      kbd.classList.toggle("held", this.held.has(kbd.dataset.key));
    }
  }
}
