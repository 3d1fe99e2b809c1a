// The recorder panel: start and stop a recording made by the core (every topic but the camera,
// which the simulator renders only while someone reads it), and the recordings folder's files,
// each with a download link. The state is polled from GET /api/recordings once a second.

import { apiFetch, getJson } from "./api.js";

const POLL_MS = 1000;
const EXCLUDE = "^/simulator/camera(/.*)?$"; // both camera topics: rendered only while read

export class RecorderPanel {
  constructor({ toggle, status, list }) {
    this.toggle = toggle;
    this.status = status;
    this.list = list;
    this.current = null; // {recording, name, messages, topics, elapsed_s} or null
    this.files = [];
    this.error = null;
    this._busy = false;
    toggle.addEventListener("click", () => this._toggle());
  }

  start() {
    this.refresh();
    setInterval(() => this.refresh(), POLL_MS);
  }

  get recording() {
    return Boolean(this.current && this.current.recording);
  }

  async refresh() {
    try {
      const state = await getJson("/api/recordings");
      this.current = state.current;
      this.files = state.files;
      this.error = null;
    } catch (error) {
      this.error = error.message;
    }
    this._render();
  }

  async _toggle() {
    if (this._busy) return;
    this._busy = true;
    const stopping = this.recording;
    try {
      const response = await apiFetch(
        stopping ? "/api/recordings/stop" : "/api/recordings",
        { method: "POST", headers: { "Content-Type": "application/json" }, body: stopping ? "" : JSON.stringify({ exclude: EXCLUDE }) },
        { userAction: true },
      );
      const body = await response.json().catch(() => ({}));
      this.error = response.ok ? null : `${response.status}: ${body.detail ?? response.statusText}`;
      if (response.ok) this.current = body;
    } catch (error) {
      this.error = `core unreachable: ${error.message}`;
    } finally {
      this._busy = false;
    }
    await this.refresh();
  }

  _render() {
    const recording = this.recording;
    this.toggle.setAttribute("aria-pressed", String(recording));
    this.toggle.textContent = recording ? "■ Stop" : "● Record";
    this.toggle.classList.toggle("recording", recording);
    if (this.error) {
      this.status.textContent = this.error;
      this.status.dataset.state = "error";
    } else if (recording) {
      const topics = Object.keys(this.current.topics || {}).length;
      this.status.textContent = `recording ${this.current.name}: ${this.current.messages} messages on ${topics} topics, ${this.current.elapsed_s.toFixed(0)} s`;
      this.status.dataset.state = "recording";
    } else {
      this.status.textContent = this.files.length ? `${this.files.length} recording(s)` : "not recording";
      this.status.dataset.state = "idle";
    }
    const items = this.files.map((file) => {
      const item = document.createElement("li");
      item.dataset.recording = file.name;
      const link = document.createElement("a");
      link.href = file.url;
      link.download = file.name;
      link.textContent = file.name;
      const size = document.createElement("span");
      size.className = "dim mono";
      size.textContent = file.recording ? " recording…" : ` ${formatSize(file.size_bytes)}`;
      item.append(link, size);
      return item;
    });
    this.list.replaceChildren(...items);
  }
}

function formatSize(bytes) {
  if (bytes < 1024) return `${bytes} B`;
  if (bytes < 1024 * 1024) return `${(bytes / 1024).toFixed(1)} KiB`;
  return `${(bytes / 1024 / 1024).toFixed(1)} MiB`;
}
