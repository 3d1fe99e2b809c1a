// The command buttons (take off, land, reset, mission start/stop) and fly-to-point: each calls
// a service through the core and shows the answer, telling success, refusal and errors apart.

import { callService } from "./api.js";

const KIND_LABEL = { success: "✓", refused: "✗ refused", error: "⚠ error", pending: "…" };

export class Commands extends EventTarget {
  constructor({ buttons, result }) {
    super();
    this.result = result;
    this.last = null; // {service, request, kind, status, message, at}
    this.buttons = buttons;
    for (const button of buttons) {
      button.addEventListener("click", () => this.call(button.dataset.service, {}, button.textContent));
    }
  }

  /** Grey out buttons whose service is not registered right now (they stay clickable). */
  updateGraph(graph) {
    const available = new Set(graph ? graph.services.map((s) => s.name) : []);
    for (const button of this.buttons) {
      const missing = !available.has(button.dataset.service);
      button.classList.toggle("unavailable", missing);
      button.title = missing
        ? `${button.dataset.service} is not registered: is its node running?`
        : `POST ${button.dataset.service}`;
    }
  }

  fly(x, y) {
    const request = { x: round(x), y: round(y) };
    return this.call("/control/fly", request, `Fly to (${request.x.toFixed(2)}, ${request.y.toFixed(2)})`);
  }

  async call(service, request, label = service) {
    this._show({ service, request, kind: "pending", status: 0, message: `${label}: calling ${service}…` });
    const answer = await callService(service, request);
    const status = answer.status ? ` (HTTP ${answer.status})` : "";
    const text =
      answer.kind === "error"
        ? `${label}${status}: ${answer.message}`
        : `${label}: ${answer.message || (answer.kind === "success" ? "ok" : "refused")}`;
    this._show({ service, request, kind: answer.kind, status: answer.status, message: text, body: answer.body });
    this.dispatchEvent(new CustomEvent("answer", { detail: this.last }));
    return answer;
  }

  _show(entry) {
    this.last = { ...entry, at: Date.now() };
    this.result.dataset.kind = entry.kind;
    this.result.dataset.service = entry.service;
    this.result.textContent = `${KIND_LABEL[entry.kind]} ${entry.message}`;
  }
}

function round(value) {
  return Math.round(value * 100) / 100;
}
