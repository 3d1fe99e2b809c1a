// The rqt_graph view: nodes (ellipses) and topics (boxes) ranked by data flow, drawn as SVG.
// Layout: drop the edges that close cycles (DFS back edges), rank by longest path, then order
// each rank by the mean position of its predecessors. Ranks are columns, left to right, when
// that fits the panel at a readable size (the expanded view); in a narrow panel they are rows,
// top to bottom, each wrapped to the panel's width, at full size (the panel scrolls down).

const SVG_NS = "http://www.w3.org/2000/svg";
// What rqt_graph calls debug: the log, clock and parameter topics, and Skydeck's own nodes (the
// core reads every topic the dashboard shows); the checkbox shows them.
const HIDDEN_TOPICS = new Set(["/rosout", "/clock", "/parameter_events"]);
const HIDDEN_NODES = new Set(["/skydeck_core", "/skydeck_launch", "/rosapi"]);
const COL_GAP = 70;
const ROW_H = 46;
const CHAR_W = 6.6;
const LINE_H = 40; // rows: one line of vertices
const RANK_GAP = 26; // rows: between ranks, for the edges
const ITEM_GAP = 14; // rows: between vertices of a line
const MIN_SCALE = 0.8; // columns shrunk below this make 11 px labels unreadable: rows instead

export class GraphDiagram {
  constructor({ container, showDebug, onPick }) {
    this.container = container;
    this.showDebug = showDebug;
    this.onPick = onPick;
    this._key = "";
    this._graph = null;
    this.orientation = null; // "columns" or "rows", as last drawn
    showDebug.addEventListener("change", () => {
      this._key = "";
      if (this._graph) this.render(this._graph);
    });
    // The panel's width decides the layout: lay out again when it changes (Expand, a resize).
    new ResizeObserver(() => {
      if (this._graph && this.container.clientWidth) this.render(this._graph);
    }).observe(container);
  }

  render(graph) {
    this._graph = graph;
    const width = this.container.clientWidth;
    const key = JSON.stringify([
      graph.nodes,
      graph.topics.map((t) => [t.name, t.publishers, t.subscribers]),
      this.showDebug.checked,
      width,
    ]);
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
    const columns = rank(vertices, edges);
    const size = placeColumns(columns, vertices);
    this.orientation = !width || size.width * MIN_SCALE <= width ? "columns" : "rows";
    if (this.orientation === "rows") placeRows(columns, vertices, width);
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
    const svg = el("svg", { viewBox: `0 0 ${width} ${height}`, width, height, class: "graph-svg", "data-orientation": this.orientation });
    const defs = el("defs");
    const marker = el("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" });
    marker.append(el("path", { d: "M0,0 L10,5 L0,10 z", class: "edge-head" }));
    defs.append(marker);
    svg.append(defs);
    for (const [from, to] of edges) {
      const d = (this.orientation === "rows" ? rowEdge : columnEdge)(vertices.get(from), vertices.get(to));
      svg.append(el("path", { d, class: "edge", "marker-end": "url(#arrow)" }));
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

/** A back edge (to a vertex to its left) loops below; a forward one bends between the columns. */
function columnEdge(a, b) {
  const x0 = a.x + a.w;
  const y0 = a.y + a.h / 2;
  const x1 = b.x;
  const y1 = b.y + b.h / 2;
  const bend = x1 > x0 ? (x1 - x0) / 2 : 60;
  const lift = x1 > x0 ? 0 : ROW_H;
  return `M${x0},${y0} C${x0 + bend},${y0 + lift} ${x1 - bend},${y1 + lift} ${x1},${y1}`;
}

/** Down from the bottom of one to the top of the other; an edge up (a cycle) loops on the right. */
function rowEdge(a, b) {
  if (b.y > a.y + a.h) {
    const x0 = a.x + a.w / 2;
    const y0 = a.y + a.h;
    const x1 = b.x + b.w / 2;
    const bend = (b.y - y0) / 2;
    return `M${x0},${y0} C${x0},${y0 + bend} ${x1},${b.y - bend} ${x1},${b.y}`;
  }
  const x0 = a.x + a.w;
  const y0 = a.y + a.h / 2;
  const x1 = b.x + b.w;
  const y1 = b.y + b.h / 2;
  return `M${x0},${y0} C${x0 + 50},${y0} ${x1 + 50},${y1} ${x1},${y1}`;
}

function buildGraph(graph, showDebug) {
  const vertices = new Map();
  const edges = [];
  const add = (id, kind, name, type, system, via) => {
    if (!vertices.has(id)) vertices.set(id, { id, kind, name, type, system, via, w: name.length * CHAR_W + 24, h: kind === "topic" ? 32 : 30 });
  };
  const shown = (node) => showDebug || !HIDDEN_NODES.has(node);
  // A node of another system (a ROS 2 node the bridge sees) is drawn apart: `vertex node ros2`.
  for (const node of graph.nodes) if (shown(node.name)) add(`n:${node.name}`, "node", node.name, undefined, node.system, node.via);
  for (const topic of graph.topics) {
    if (!showDebug && HIDDEN_TOPICS.has(topic.name)) continue;
    const publishers = topic.publishers.filter(shown);
    const subscribers = topic.subscribers.filter(shown);
    if (!showDebug && !publishers.length && !subscribers.length) continue; // only Skydeck's own use it
    add(`t:${topic.name}`, "topic", topic.name, topic.type);
    for (const p of publishers) {
      add(`n:${p}`, "node", p);
      edges.push([`n:${p}`, `t:${topic.name}`]);
    }
    for (const s of subscribers) {
      add(`n:${s}`, "node", s);
      edges.push([`t:${topic.name}`, `n:${s}`]);
    }
  }
  return { vertices, edges };
}

/** The ranks (columns, left to right, each a list of vertex ids) of the graph's vertices. */
function rank(vertices, edges) {
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
  const ranks = new Map(ids.map((id) => [id, 0]));
  const preds = new Map(ids.map((id) => [id, []]));
  for (const id of order.reverse()) {
    for (const next of forward.get(id)) {
      ranks.set(next, Math.max(ranks.get(next), ranks.get(id) + 1));
      preds.get(next).push(id);
    }
  }
  const columns = [];
  for (const id of order) {
    const r = ranks.get(id);
    (columns[r] ||= []).push(id);
  }
  for (const id of ids) vertices.get(id).preds = preds.get(id);
  return columns.filter(Boolean);
}

/** Ranks as columns, left to right, each ordered by its predecessors' rows; the drawing's size. */
function placeColumns(columns, vertices) {
  let x = 10;
  let height = 0;
  const position = new Map();
  for (const column of columns) {
    column.sort((a, b) => mean(vertices.get(a).preds, position) - mean(vertices.get(b).preds, position) || a.localeCompare(b));
    const width = Math.max(...column.map((id) => vertices.get(id).w));
    column.forEach((id, i) => {
      const v = vertices.get(id);
      v.x = x + (width - v.w) / 2;
      v.y = 10 + i * ROW_H;
      position.set(id, i);
      height = Math.max(height, v.y + v.h);
    });
    x += width + COL_GAP;
  }
  return { width: x - COL_GAP + 10, height: height + 10 };
}

/** Ranks as rows, top to bottom, each ordered by its predecessors' places and wrapped to ``width``. */
function placeRows(columns, vertices, width) {
  let y = 10;
  const position = new Map();
  for (const column of columns) {
    column.sort((a, b) => mean(vertices.get(a).preds, position) - mean(vertices.get(b).preds, position) || a.localeCompare(b));
    const lines = [[]];
    let used = 0;
    for (const id of column) {
      const w = vertices.get(id).w;
      if (lines.at(-1).length && used + w > width - 20) {
        lines.push([]);
        used = 0;
      }
      lines.at(-1).push(id);
      used += w + ITEM_GAP;
    }
    for (const line of lines) {
      const lineWidth = line.reduce((sum, id) => sum + vertices.get(id).w, 0) + ITEM_GAP * (line.length - 1);
      let x = Math.max(10, (width - lineWidth) / 2);
      for (const id of line) {
        const v = vertices.get(id);
        v.x = x;
        v.y = y;
        position.set(id, x + v.w / 2);
        x += v.w + ITEM_GAP;
      }
      y += LINE_H;
    }
    y += RANK_GAP;
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
