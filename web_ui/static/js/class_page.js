// The class page (the instructor's, issue 35): every student's robot in one 3D scene and a
// table (student, connected nodes, last message age, grade) from GET /api/class, polled once a
// second while shown; clicking a student shows their topics (each opens in the Inspector).

import { getJson } from "./api.js";
import { cell } from "./graph.js";

const POLL_MS = 1000;

function age(seconds) {
  if (seconds == null) return "–";
  return seconds < 60 ? `${seconds.toFixed(1)} s ago` : `${Math.round(seconds / 60)} min ago`;
}

function grade(row) {
  const g = row.grade;
  if (!g) return "–";
  const score = typeof g.score === "number" ? g.score.toFixed(2) : "?";
  return g.passed === true ? `${score} ✓` : g.passed === false ? `${score} ✗` : score;
}

export class ClassPage {
  constructor({ tab, table, detail, assignment, note, canvas, graph, onPick }) {
    this.tab = tab;
    this.table = table;
    this.detail = detail;
    this.assignment = assignment;
    this.note = note;
    this.canvas = canvas;
    this.graph = graph;
    this.onPick = onPick;
    this.rows = [];
    this.selected = null;
    this.error = null;
    this.polls = 0;
    this.shown = false;
    this.scene = null; // loaded with three.js the first time the page is shown
    this._timer = 0;
    graph.addEventListener("update", () => this.renderDetail());
  }

  /** Whether the page's token may see the class page (the tab is hidden otherwise). */
  setAvailable(available) {
    this.tab.hidden = !available;
    if (!available) this.setShown(false);
  }

  setShown(shown) {
    if (shown === this.shown) return;
    this.shown = shown;
    clearTimeout(this._timer);
    if (shown) {
      this._poll();
      this._loadScene();
    }
    if (this.scene) this.scene.setShown(shown);
  }

  async _loadScene() {
    if (this.scene) return;
    const { ClassScene } = await import("./class_scene.js");
    this.scene ??= new ClassScene(this.canvas);
    this.scene.setSelected(this.selected);
    this.scene.setShown(this.shown);
  }

  async _poll() {
    if (!this.shown) return;
    try {
      const answer = await getJson("/api/class");
      this.rows = answer.students;
      this.error = null;
      this.assignment.textContent = answer.assignment ? `assignment: ${answer.assignment}` : "no grades yet";
      this.note.textContent = answer.gradebook && answer.gradebook.error ? answer.gradebook.error : "";
    } catch (error) {
      this.error = error.message;
      this.note.textContent = `the class: ${error.message}`;
    }
    this.polls += 1;
    this.render();
    if (this.shown) this._timer = setTimeout(() => this._poll(), POLL_MS);
  }

  render() {
    const body = this.table.tBodies[0];
    body.replaceChildren(
      ...this.rows.map((row) => {
        const tr = document.createElement("tr");
        tr.className = "pickable";
        tr.dataset.student = row.name;
        tr.setAttribute("aria-selected", String(row.name === this.selected));
        const nodes = row.nodes.length ? row.nodes.map((n) => n.slice(row.namespace.length + 1)).join(", ") : "none";
        tr.append(cell(row.name), cell(nodes, "flow"), cell(age(row.last_message_age_s), "num"), cell(grade(row), "num"));
        if (row.grade && row.grade.passed === false) tr.dataset.failed = "";
        tr.addEventListener("click", () => this.select(row.name));
        return tr;
      }),
    );
    this.renderDetail();
  }

  select(name) {
    this.selected = name;
    for (const tr of this.table.tBodies[0].rows) tr.setAttribute("aria-selected", String(tr.dataset.student === name));
    if (this.scene) this.scene.setSelected(name);
    this.renderDetail();
  }

  /** The selected student's topics (from the graph), each a link to the Inspector. */
  topicsOf(name) {
    const graph = this.graph.graph;
    if (!graph || !name) return [];
    const prefix = `/${name}/`;
    return graph.topics.filter((t) => t.name.startsWith(prefix));
  }

  renderDetail() {
    if (!this.selected) return;
    const row = this.rows.find((r) => r.name === this.selected);
    const title = document.createElement("strong");
    title.textContent = `${this.selected}'s topics`;
    const list = document.createElement("ul");
    list.className = "nodes";
    for (const topic of this.topicsOf(this.selected)) {
      const item = document.createElement("li");
      const link = document.createElement("button");
      link.type = "button";
      link.className = "ghost small";
      link.textContent = topic.name;
      link.title = `${topic.type || "?"}: inspect it`;
      link.addEventListener("click", () => this.onPick(topic.name));
      const rate = typeof topic.rate_hz === "number" ? ` ${topic.rate_hz.toFixed(1)} Hz` : "";
      item.append(link, document.createTextNode(` ${topic.type || ""}${rate}`));
      list.append(item);
    }
    const criteria = document.createElement("ul");
    criteria.className = "nodes";
    for (const c of (row && row.grade && row.grade.criteria) || []) {
      const item = document.createElement("li");
      item.textContent = `${c.passed ? "✓" : "✗"} ${c.name}: ${c.figure ?? ""} ${c.verdict ?? ""}`.trim();
      criteria.append(item);
    }
    this.detail.classList.remove("dim");
    this.detail.replaceChildren(title, list, ...(criteria.children.length ? [criteria] : []));
  }

  snapshot() {
    return {
      shown: this.shown,
      available: !this.tab.hidden,
      polls: this.polls,
      error: this.error,
      selected: this.selected,
      rows: this.rows.map((r) => ({ ...r })),
      topics: this.topicsOf(this.selected).map((t) => t.name),
      scene: this.scene ? this.scene.snapshot() : null,
    };
  }
}
