// The rqt_graph view: nodes (ellipses) and topics (boxes) in columns by data flow, drawn as SVG.
// Layout: drop the edges that close cycles (DFS back edges), rank by longest path, then order
// each column by the mean position of its predecessors.

const SVG_NS = "http://www.w3.org/2000/svg";
const HIDDEN_TOPICS = new Set(["/rosout", "/clock", "/parameter_events"]);
const COL_GAP = 70;
const ROW_H = 46;
const CHAR_W = 6.6;

export class GraphDiagram {
  constructor({ container, showDebug, onPick }) {
    this.container = container;
    this.showDebug = showDebug;
    this.onPick = onPick;
    this._key = "";
    this._graph = null;
    showDebug.addEventListener("change", () => {
      this._key = "";
      if (this._graph) this.render(this._graph);
    });
  }

  render(graph) {
    this._graph = graph;
    const key = JSON.stringify([graph.nodes, graph.topics.map((t) => [t.name, t.publishers, t.subscribers]), this.showDebug.checked]);
    if (key === this._key) {
      this._updateRates(graph);
      return;
    }
    this._key = key;
    const { vertices, edges } = buildGraph(graph, this.showDebug.checked);
    if (!vertices.size) {
      this.container.textContent = "Nothing registered yet.";
      return;
    }
    layout(vertices, edges);
    this.container.replaceChildren(this._svg(vertices, edges));
    this._updateRates(graph);
  }

  _updateRates(graph) {
    for (const topic of graph.topics) {
      const label = this.container.querySelector(`[data-rate-for="${CSS.escape(topic.name)}"]`);
      if (label) label.textContent = typeof topic.rate_hz === "number" ? `${topic.rate_hz.toFixed(1)} Hz` : "";
    }
  }

  _svg(vertices, edges) {
    const all = [...vertices.values()];
    const width = Math.max(...all.map((v) => v.x + v.w)) + 10;
    const height = Math.max(...all.map((v) => v.y + v.h)) + 10;
    const svg = el("svg", { viewBox: `0 0 ${width} ${height}`, width, height, class: "graph-svg" });
    const defs = el("defs");
    const marker = el("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" });
    marker.append(el("path", { d: "M0,0 L10,5 L0,10 z", class: "edge-head" }));
    defs.append(marker);
    svg.append(defs);
    for (const [from, to] of edges) {
      const a = vertices.get(from);
      const b = vertices.get(to);
      const x0 = a.x + a.w;
      const y0 = a.y + a.h / 2;
      const x1 = b.x;
      const y1 = b.y + b.h / 2;
      const bend = x1 > x0 ? (x1 - x0) / 2 : 60;
      const lift = x1 > x0 ? 0 : ROW_H; // back edges loop below
      svg.append(
        el("path", {
          d: `M${x0},${y0} C${x0 + bend},${y0 + lift} ${x1 - bend},${y1 + lift} ${x1},${y1}`,
          class: "edge",
          "marker-end": "url(#arrow)",
        }),
      );
    }
    for (const v of all) {
      const group = el("g", { class: `vertex ${v.kind}${v.system ? ` ${v.system}` : ""}`, "data-name": v.name });
      if (v.kind === "node") {
        group.append(el("ellipse", { cx: v.x + v.w / 2, cy: v.y + v.h / 2, rx: v.w / 2, ry: v.h / 2 }));
      } else {
        group.append(el("rect", { x: v.x, y: v.y, width: v.w, height: v.h, rx: 4 }));
      }
      const label = el("text", { x: v.x + v.w / 2, y: v.y + (v.kind === "topic" ? 14 : v.h / 2 + 4), "text-anchor": "middle" });
      label.textContent = v.name;
      group.append(label);
      if (v.kind === "topic") {
        const rate = el("text", { x: v.x + v.w / 2, y: v.y + 27, "text-anchor": "middle", class: "rate", "data-rate-for": v.name });
        group.append(rate);
        group.addEventListener("click", () => this.onPick(v.name));
      }
      const title = el("title");
      title.textContent = v.kind === "topic" ? `${v.name} (${v.type})` : v.system ? `${v.name} (ROS 2, via ${v.via})` : v.name;
      group.append(title);
      svg.append(group);
    }
    return svg;
  }
}

function buildGraph(graph, showDebug) {
  const vertices = new Map();
  const edges = [];
  const add = (id, kind, name, type, system, via) => {
    if (!vertices.has(id)) vertices.set(id, { id, kind, name, type, system, via, w: name.length * CHAR_W + 24, h: kind === "topic" ? 32 : 30 });
  };
  // A node of another system (a ROS 2 node the bridge sees) is drawn apart: `vertex node ros2`.
  for (const node of graph.nodes) add(`n:${node.name}`, "node", node.name, undefined, node.system, node.via);
  for (const topic of graph.topics) {
    if (!showDebug && HIDDEN_TOPICS.has(topic.name)) continue;
    add(`t:${topic.name}`, "topic", topic.name, topic.type);
    for (const p of topic.publishers) {
      add(`n:${p}`, "node", p);
      edges.push([`n:${p}`, `t:${topic.name}`]);
    }
    for (const s of topic.subscribers) {
      add(`n:${s}`, "node", s);
      edges.push([`t:${topic.name}`, `n:${s}`]);
    }
  }
  return { vertices, edges };
}

function layout(vertices, edges) {
  const out = new Map([...vertices.keys()].map((id) => [id, []]));
  const indegree = new Map([...vertices.keys()].map((id) => [id, 0]));
  for (const [a, b] of edges) {
    out.get(a).push(b);
    indegree.set(b, indegree.get(b) + 1);
  }
  // DFS from the sources first; an edge to a vertex still on the stack closes a cycle.
  const state = new Map();
  const forward = new Map([...vertices.keys()].map((id) => [id, []]));
  const order = [];
  const visit = (id) => {
    state.set(id, "open");
    for (const next of out.get(id)) {
      if (state.get(next) === "open") continue;
      forward.get(id).push(next);
      if (!state.has(next)) visit(next);
    }
    state.set(id, "done");
    order.push(id);
  };
  const ids = [...vertices.keys()].sort();
  for (const id of ids.filter((i) => indegree.get(i) === 0)) if (!state.has(id)) visit(id);
  for (const id of ids) if (!state.has(id)) visit(id);
  // Longest path over the remaining DAG, in topological order (reverse post-order).
  const rank = new Map(ids.map((id) => [id, 0]));
  const preds = new Map(ids.map((id) => [id, []]));
  for (const id of order.reverse()) {
    for (const next of forward.get(id)) {
      rank.set(next, Math.max(rank.get(next), rank.get(id) + 1));
      preds.get(next).push(id);
    }
  }
  const columns = [];
  for (const id of order) {
    const r = rank.get(id);
    (columns[r] ||= []).push(id);
  }
  let x = 10;
  const position = new Map();
  for (const column of columns) {
    if (!column) continue;
    column.sort((a, b) => mean(preds.get(a), position) - mean(preds.get(b), position) || a.localeCompare(b));
    const width = Math.max(...column.map((id) => vertices.get(id).w));
    column.forEach((id, i) => {
      const v = vertices.get(id);
      v.x = x + (width - v.w) / 2;
      v.y = 10 + i * ROW_H;
      position.set(id, i);
    });
    x += width + COL_GAP;
  }
}

function mean(ids, position) {
  const known = ids.filter((id) => position.has(id)).map((id) => position.get(id));
  return known.length ? known.reduce((a, b) => a + b, 0) / known.length : 0;
}

function el(tag, attributes = {}) {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, String(value));
  return node;
}
