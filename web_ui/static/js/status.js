// Connection status: the header pill and the banner that says what is wrong and what to do
// (core unreachable, simulator absent or not publishing).

const STALE_POSE_S = 2;
const STARTUP_GRACE_MS = 3000; // sockets are still connecting: no "not publishing" yet

export class StatusBanner {
  constructor({ banner, pill, summary, graph, world }) {
    this.banner = banner;
    this.pill = pill;
    this.summary = summary;
    this.graph = graph;
    this.world = world;
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
      const pose = graph.graph.topics.find((t) => t.name === "/drone/pose");
      const age = world.poseAgeSeconds();
      if (!pose || !pose.publishers.length) {
        state = "warn";
        message = "Simulator not running: nothing publishes /drone/pose. Start it with `skydeck run sim` (or `make up`).";
      } else if (age > STALE_POSE_S && !(age === Infinity && performance.now() < STARTUP_GRACE_MS)) {
        state = "warn";
        message = Number.isFinite(age)
          ? `Simulator not publishing: no /drone/pose for ${age.toFixed(0)} s (${pose.publishers.join(", ")} registered).`
          : `Simulator not publishing: no /drone/pose received yet from ${pose.publishers.join(", ")}.`;
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
}
