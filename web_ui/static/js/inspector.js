// The inspector: echo any topic live (`rostopic echo`, throttled, pausable) and publish a
// message of its type from a form pre-filled with the type's default; or call any service.

import { TopicSocket, callService, getJson } from "./api.js";
import { MessageForm } from "./form_fields.js";

const ECHO_KEEP = 20;
const LONG_STRING = 160;

export class Inspector {
  constructor(elements, graph) {
    this.e = elements;
    this.graph = graph;
    this.name = "";
    this.kind = null; // "topic" | "service"
    this.type = null;
    this.socket = null;
    this.publisher = null;
    this.paused = false;
    this.messages = []; // last few frames, as text
    this.received = 0;
    this._repeat = null;
    this._arrivals = [];
    this._interfaces = null;
    this.form = new MessageForm({ fields: elements.fields, json: elements.json });
    elements.form.addEventListener("submit", (event) => {
      event.preventDefault();
      this.inspect(elements.name.value.trim());
    });
    elements.pause.addEventListener("click", () => this._togglePause());
    elements.send.addEventListener("click", () => this._send());
    elements.repeat.addEventListener("change", () => this._stopRepeat());
    elements.type.addEventListener("change", () => this._chooseType(elements.type.value));
  }

  updateGraph(graph) {
    const names = [...graph.topics.map((t) => t.name), ...graph.services.map((s) => s.name)].sort();
    const key = names.join();
    if (key !== this._namesKey) {
      this._namesKey = key;
      this.e.names.replaceChildren(...names.map((n) => new Option(n, n)));
    }
  }

  /** Show `name` (a topic or a service). */
  async inspect(name) {
    if (!name) return;
    if (!name.startsWith("/")) name = `/${name}`;
    this._close();
    this.name = name;
    this.e.name.value = name;
    const service = this.graph.service(name);
    this.kind = service ? "service" : "topic";
    this.type = service ? service.type : this.graph.topicType(name);
    this.e.echoBox.hidden = this.kind !== "topic";
    this.e.sendBox.hidden = false;
    this.e.sendTitle.textContent = this.kind === "service" ? `Call ${name}` : `Publish on ${name}`;
    this.e.send.textContent = this.kind === "service" ? "Call" : "Publish";
    this.e.repeatRow.hidden = this.kind === "service";
    this.e.typeRow.hidden = !(this.kind === "topic" && !this.type);
    this._result("none", "");
    if (this.kind === "topic") {
      this.e.info.textContent = this.type ? `topic ${name} · ${this.type}` : `topic ${name}: not in the graph yet; choose a type to publish it`;
      this._openEcho();
      if (!this.type) await this._offerTypes();
    } else {
      this.e.info.textContent = `service ${name} · ${this.type} · on ${service.node}`;
    }
    if (this.type) await this._loadInterface(this.type);
  }

  _openEcho() {
    this.messages = [];
    this.received = 0;
    this._arrivals = [];
    this.e.echo.textContent = "waiting for a message…";
    const heavy = (this.type || "").includes("Image");
    this.socket = new TopicSocket(this.name, {
      rate: heavy ? 1 : 10,
      mode: "subscribe",
      onMessage: (msg) => this._onMessage(msg),
      onError: (text) => this._result("error", text),
    }).open();
    // Publishing goes on its own socket, as `rostopic pub` beside `rostopic echo`: the core never
    // sends a socket its own frames back, and the echo above shows what was published.
    if (this.type) {
      this.publisher = new TopicSocket(this.name, {
        mode: "publish",
        type: this.graph.topicType(this.name) ? undefined : this.type,
        onError: (text) => this._result("error", text),
      }).open();
    }
    this._stats();
  }

  _onMessage(msg) {
    this.received += 1;
    const now = performance.now();
    this._arrivals.push(now);
    while (this._arrivals.length && now - this._arrivals[0] > 3000) this._arrivals.shift();
    this.messages.push(JSON.stringify(msg, abbreviate, 2));
    if (this.messages.length > ECHO_KEEP) this.messages.shift();
    if (!this.paused) {
      this.e.echo.textContent = this.messages.join("\n---\n");
      this.e.echo.scrollTop = this.e.echo.scrollHeight;
    }
    this._stats();
  }

  _stats() {
    const rate = this._arrivals.length > 1 ? ((this._arrivals.length - 1) * 1000) / (this._arrivals.at(-1) - this._arrivals[0]) : 0;
    this.e.stats.textContent = `${this.received} received · ~${rate.toFixed(1)} Hz shown (throttled)${this.paused ? " · paused" : ""}`;
  }

  _togglePause() {
    this.paused = !this.paused;
    this.e.pause.textContent = this.paused ? "Resume" : "Pause";
    this.e.pause.setAttribute("aria-pressed", String(this.paused));
    if (!this.paused) this.e.echo.textContent = this.messages.join("\n---\n");
    this._stats();
  }

  async _offerTypes() {
    if (!this._interfaces) {
      try {
        this._interfaces = (await getJson("/api/interfaces")).interfaces.filter((i) => i.kind === "msg").map((i) => i.name);
      } catch (error) {
        this._result("error", `cannot list types: ${error.message}`);
        return;
      }
    }
    this.e.type.replaceChildren(new Option("choose a type…", ""), ...this._interfaces.map((n) => new Option(n, n)));
  }

  async _chooseType(type) {
    if (!type) return;
    this.type = type;
    this._closeSockets();
    this._openEcho();
    await this._loadInterface(type);
  }

  async _loadInterface(type) {
    try {
      const info = await getJson(`/api/interfaces/${type}`);
      this.e.typeText.textContent = info.text;
      this.form.set(this.kind === "service" ? info.default.request : info.default);
    } catch (error) {
      this.e.typeText.textContent = "";
      this.form.set({});
      this._result("error", `cannot load ${type}: ${error.message}`);
    }
  }

  async _send() {
    let msg;
    try {
      msg = this.form.read();
    } catch (error) {
      this._result("error", `not valid JSON: ${error.message}`);
      return;
    }
    if (this.kind === "service") {
      this._result("pending", `calling ${this.name}…`);
      const answer = await callService(this.name, msg);
      this._result(answer.kind, describeAnswer(answer));
      return;
    }
    if (!this.type) {
      this._result("error", "choose the topic's type first");
      return;
    }
    const hz = Number(this.e.repeat.value);
    this._stopRepeat();
    const once = () => {
      if (this.publisher && this.publisher.publish(msg)) this._result("success", `published on ${this.name}${hz ? ` at ${hz} Hz` : ""}`);
      else this._result("error", `${this.name}: socket not open yet; try again`);
    };
    once();
    if (hz) this._repeat = setInterval(once, 1000 / hz);
  }

  _stopRepeat() {
    clearInterval(this._repeat);
    this._repeat = null;
  }

  _result(kind, text) {
    this.e.result.dataset.kind = kind;
    this.e.result.textContent = text;
  }

  _closeSockets() {
    for (const socket of [this.socket, this.publisher]) if (socket) socket.close();
    this.socket = this.publisher = null;
  }

  _close() {
    this._stopRepeat();
    this._closeSockets();
    this.paused = false;
    this.e.pause.textContent = "Pause";
  }
}

function describeAnswer(answer) {
  if (answer.kind === "error") return `⚠ HTTP ${answer.status || "–"}: ${answer.message}`;
  const { success, message, ...rest } = answer.body || {};
  const extra = Object.keys(rest).length ? ` ${JSON.stringify(rest)}` : "";
  return `${answer.kind === "success" ? "✓ success" : "✗ refused"}: ${message ?? ""}${extra}`;
}

// Camera frames and other long strings would drown the echo: show their length instead.
function abbreviate(key, value) {
  if (typeof value === "string" && value.length > LONG_STRING) return `<${value.length} characters>`;
  return value;
}
