// The system's graph (`rostopic list`, `rosservice list`, `rosnode list`): polled from the core
// about once a second; listeners get every new graph, or the error when the core is away.

import { getJson } from "./api.js";

const POLL_MS = 1000;

export class GraphPoller extends EventTarget {
  constructor() {
    super();
    this.graph = null;
    this.raw = null; // the core's last answer, before the filter
    this.error = null;
    this.failures = 0;
    this.filter = (graph) => graph; // what the page's token may see of it (access.js)
  }

  start() {
    const poll = async () => {
      try {
        this.raw = await getJson("/api/graph");
        this.graph = this.filter(this.raw);
        this.error = null;
        this.failures = 0;
      } catch (error) {
        this.error = error;
        this.failures += 1;
      }
      this.dispatchEvent(new Event("update"));
      setTimeout(poll, this.failures ? Math.min(POLL_MS * this.failures, 5000) : POLL_MS);
    };
    poll();
  }

  /** Filter the last graph again (the token's rights changed) and tell the page at once, so no
   * graph fetched before the core said who the token is stays shown until the next poll. */
  refilter() {
    if (this.raw === null) return;
    this.graph = this.filter(this.raw);
    this.dispatchEvent(new Event("update"));
  }

  topicType(name) {
    const topic = this.graph && this.graph.topics.find((t) => t.name === name);
    return topic ? topic.type : null;
  }

  service(name) {
    return (this.graph && this.graph.services.find((s) => s.name === name)) || null;
  }
}

/** A table cell holding `text` (its class `className`, if given). */
export function cell(text, className) {
  const td = document.createElement("td");
  td.textContent = text;
  if (className) td.className = className;
  return td;
}

function shortType(type) {
  // Like rostopic's "pkg/Type"; a zero-width space after the slash lets long names wrap there.
  return type.replace("/msg/", "/\u200b").replace("/srv/", "/\u200b");
}

/** The Topics tab: topics with types and live rates, services, nodes. */
export class GraphTables {
  constructor({ topics, services, nodes, onPick }) {
    this.topics = topics.tBodies[0];
    this.services = services.tBodies[0];
    this.nodes = nodes;
    this.onPick = onPick;
    this._key = "";
  }

  render(graph) {
    const key = JSON.stringify(graph);
    if (key === this._key) return;
    this._key = key;
    this._renderTopics(graph.topics);
    this._renderServices(graph.services);
    this._renderNodes(graph.nodes);
  }

  _renderTopics(topics) {
    const rows = [...topics].sort((a, b) => a.name.localeCompare(b.name)).map((topic) => {
      const tr = document.createElement("tr");
      tr.dataset.topic = topic.name;
      tr.dataset.type = topic.type;
      tr.title = `inspect ${topic.name} (${topic.type})`;
      tr.className = "pickable";
      const rate = typeof topic.rate_hz === "number" ? topic.rate_hz.toFixed(1) : "–";
      const flow = `${topic.publishers.join(", ") || "∅"} → ${topic.subscribers.join(", ") || "∅"}`;
      tr.append(cell(topic.name, "mono"), cell(shortType(topic.type), "dim type"), cell(rate, "num"), cell(flow, "dim small-text flow"));
      tr.addEventListener("click", () => this.onPick(topic.name));
      return tr;
    });
    if (!rows.length) rows.push(emptyRow(4, "no topics: is anything running?"));
    this.topics.replaceChildren(...rows);
  }

  _renderServices(services) {
    const rows = [...services].sort((a, b) => a.name.localeCompare(b.name)).map((service) => {
      const tr = document.createElement("tr");
      tr.dataset.service = service.name;
      tr.dataset.type = service.type;
      tr.title = `call ${service.name} (${service.type})`;
      tr.className = "pickable";
      tr.append(cell(service.name, "mono"), cell(shortType(service.type), "dim type"), cell(service.node, "dim"));
      tr.addEventListener("click", () => this.onPick(service.name));
      return tr;
    });
    if (!rows.length) rows.push(emptyRow(3, "no services"));
    this.services.replaceChildren(...rows);
  }

  _renderNodes(nodes) {
    const items = [...nodes].sort((a, b) => a.name.localeCompare(b.name)).map((node) => {
      const li = document.createElement("li");
      li.dataset.node = node.name;
      const title = document.createElement("div");
      title.innerHTML = "<strong class='mono'></strong> <span class='dim'></span>";
      title.firstChild.textContent = node.name;
      title.lastChild.textContent = node.system
        ? `ROS 2 node, via ${node.via}` // another system's node, seen by a bridge
        : `${node.url}${node.pid ? `, pid ${node.pid}` : ""}`;
      const detail = document.createElement("div");
      detail.className = "dim small-text";
      detail.textContent =
        `pub ${node.publications.length}: ${node.publications.join(", ") || "–"} · ` +
        `sub ${node.subscriptions.length}: ${node.subscriptions.join(", ") || "–"} · ` +
        `srv ${node.services.length}: ${node.services.join(", ") || "–"}`;
      li.append(title, detail);
      return li;
    });
    if (!items.length) {
      const li = document.createElement("li");
      li.className = "dim";
      li.textContent = "no nodes registered";
      items.push(li);
    }
    this.nodes.replaceChildren(...items);
  }
}

function emptyRow(span, text) {
  const tr = document.createElement("tr");
  const td = cell(text, "dim");
  td.colSpan = span;
  tr.append(td);
  return tr;
}
