// Keyboard teleop: publishes geometry_msgs/msg/Twist on /drone/cmd_vel at 10 Hz while keys are
// held and one zero Twist on release. Off by default; keys typed into form fields never count.

import { TopicSocket } from "./api.js";

const TOPIC = "/drone/cmd_vel";
const TYPE = "geometry_msgs/msg/Twist";
const PERIOD_MS = 100;
const YAW_RATE = 1.0; // rad/s
const CLIMB_RATE = 1.0; // m/s

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
  constructor({ toggle, speed, speedLabel, keysView, note }) {
    this.toggle = toggle;
    this.note = note;
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
      speedLabel.textContent = Number(speed.value).toFixed(1);
    });
    window.addEventListener("keydown", (event) => this._key(event, true));
    window.addEventListener("keyup", (event) => this._key(event, false));
    window.addEventListener("blur", () => this._releaseAll());
    document.addEventListener("visibilitychange", () => this._releaseAll());
  }

  setEnabled(enabled) {
    if (enabled === this.enabled) return;
    if (!enabled) this._releaseAll();
    this.enabled = enabled;
    this.toggle.setAttribute("aria-pressed", String(enabled));
    this.toggle.textContent = enabled ? "Teleop ON" : "Teleop off";
    this.keysView.classList.toggle("dim", !enabled);
    this.note.textContent = enabled
      ? "On: WASD / arrows move (as on the map), R/F up/down, Q/E yaw, space stops. Typing in a field never drives."
      : "Off: keys do nothing. Control's setpoint stream, when active, wins over teleop.";
    if (enabled) {
      this.toggle.blur(); // so space and arrows reach the window, not the button
      this.socket = new TopicSocket(TOPIC, { type: TYPE, mode: "publish" }).open();
    } else if (this.socket) {
      const socket = this.socket;
      this.socket = null;
      setTimeout(() => socket.close(), 300); // let the zero Twist leave first
    }
  }

  /** The Twist for the keys held now. */
  twist() {
    const v = Number(this.speed.value);
    const h = this.held;
    const axis = (plus, minus) => (h.has(plus) ? 1 : 0) - (h.has(minus) ? 1 : 0);
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
