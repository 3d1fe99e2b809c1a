// The /rosout console (rqt_console): newest at the bottom, filterable by level, node and text,
// bounded to the last 500 entries.

import { getJson, TopicSocket } from "./api.js";
import { stampSeconds } from "./geometry.js";

const MAX_ENTRIES = 500;
const BACKLOG_LINES = 200; // of the core's last /rosout lines, shown when the page opens
const LEVELS = { 10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL" };

export class LogConsole {
  constructor({ container, level, node, filter, clear, count }) {
    this.container = container;
    this.level = level;
    this.node = node;
    this.filter = filter;
    this.count = count;
    this.entries = [];
    this.nodes = new Set();
    for (const control of [level, node]) control.addEventListener("change", () => this._renderAll());
    filter.addEventListener("input", () => this._renderAll());
    clear.addEventListener("click", () => {
      this.entries = [];
      this._renderAll();
    });
  }

  /**
   * The core's backlog first (GET /api/rosout: what was said before the page came), then the
   * stream. The stream opens first and waits, so no line falls between the two; a line in both
   * (said while the backlog was fetched) is shown once.
   */
  async start() {
    const early = [];
    let backlogShown = false;
    this.socket = new TopicSocket("/rosout", {
      queue: 200,
      onMessage: (msg) => (backlogShown ? this.add(msg) : early.push(msg)),
    }).openWhenPublished();
    let backlog = [];
    try {
      backlog = await getJson(`/api/rosout?limit=${BACKLOG_LINES}`);
    } catch {
      // an older core, or none yet: the stream alone, as before
    }
    const seen = new Set(backlog.map((msg) => JSON.stringify(msg)));
    for (const msg of backlog) this.add(msg);
    for (const msg of early) if (!seen.has(JSON.stringify(msg))) this.add(msg);
    backlogShown = true;
  }

  add(msg) {
    const entry = {
      level: Number(msg.level) || 20,
      name: msg.name || "?",
      msg: String(msg.msg ?? ""),
      where: msg.file ? `${msg.file}:${msg.line} (${msg.function})` : "",
      time: stampSeconds(msg.stamp),
    };
    this.entries.push(entry);
    if (!this.nodes.has(entry.name)) {
      this.nodes.add(entry.name);
      this.node.append(new Option(entry.name, entry.name));
    }
    let trimmed = false;
    if (this.entries.length > MAX_ENTRIES) {
      this.entries.splice(0, this.entries.length - MAX_ENTRIES);
      trimmed = true;
    }
    if (this._matches(entry)) {
      const stick = this._atBottom();
      this.container.append(this._row(entry));
      if (trimmed) this._trimDom();
      if (stick) this.container.scrollTop = this.container.scrollHeight;
    }
    this._updateCount();
  }

  _matches(entry) {
    const text = this.filter.value.trim().toLowerCase();
    return (
      entry.level >= Number(this.level.value) &&
      (!this.node.value || entry.name === this.node.value) &&
      (!text || entry.msg.toLowerCase().includes(text) || entry.name.toLowerCase().includes(text))
    );
  }

  _row(entry) {
    const div = document.createElement("div");
    div.className = "log-entry";
    div.dataset.level = LEVELS[entry.level] || String(entry.level);
    div.title = entry.where;
    const time = entry.time ? new Date(entry.time * 1000).toLocaleTimeString([], { hour12: false }) : "";
    const parts = [
      ["log-time", time],
      ["log-level", div.dataset.level],
      ["log-node", `[${entry.name}]`],
      ["log-msg", entry.msg],
    ];
    for (const [className, text] of parts) {
      const span = document.createElement("span");
      span.className = className;
      span.textContent = text;
      div.append(span);
    }
    return div;
  }

  _trimDom() {
    // Entries that fell out of the buffer leave the DOM too.
    const shown = this.entries.filter((e) => this._matches(e)).length;
    while (this.container.childElementCount > shown) this.container.firstElementChild.remove();
  }

  _renderAll() {
    this.container.replaceChildren(...this.entries.filter((e) => this._matches(e)).map((e) => this._row(e)));
    this.container.scrollTop = this.container.scrollHeight;
    this._updateCount();
  }

  _atBottom() {
    const c = this.container;
    return c.scrollHeight - c.scrollTop - c.clientHeight < 30;
  }

  _updateCount() {
    this.count.textContent = `${this.container.childElementCount} shown / ${this.entries.length} kept`;
  }
}
