// The Actions tab (`ros2 action list` with its goals): every ROS 2 action in the graph (a node
// serves NAME/_action/send_goal) and the goals its server holds, from the action's status topic
// (latched: each goal and its status, until the server forgets its result) and its feedback
// topic (the latest feedback of each goal). Both are read only while the tab is shown.

import { TopicSocket } from "./api.js";

const ACTION_INFIX = "/_action/";
const SEND_GOAL = `${ACTION_INFIX}send_goal`;
const STATUS_NAMES = ["UNKNOWN", "ACCEPTED", "EXECUTING", "CANCELING", "SUCCEEDED", "CANCELED", "ABORTED"];
const ACTIVE = new Set([1, 2, 3]);
const FEEDBACK_RATE_HZ = 10; // the newest feedback wins: enough to read it
const FEEDBACK_CHARS = 160;

/** The actions of a graph: [{name, type}], by name. */
export function actionsIn(graph) {
  const found = new Map();
  for (const service of graph.services) {
    if (!service.name.endsWith(SEND_GOAL)) continue;
    const name = service.name.slice(0, -SEND_GOAL.length);
    if (name) found.set(name, { name, type: service.type.replace(/_SendGoal$/, "") });
  }
  return [...found.values()].sort((a, b) => a.name.localeCompare(b.name));
}

/** A goal ID (unique_identifier_msgs/UUID's bytes: base64 in JSON, or a list) as 32 hex digits. */
export function goalIdHex(uuid) {
  const bytes = typeof uuid === "string" ? Array.from(atob(uuid), (c) => c.charCodeAt(0)) : Array.from(uuid || []);
  return bytes.map((b) => b.toString(16).padStart(2, "0")).join("");
}

export class ActionsPanel {
  constructor({ table, empty }) {
    this.body = table.tBodies[0];
    this.empty = empty;
    this.actions = [];
    this.visible = false;
    this._sockets = new Map(); // action name -> [status socket, feedback socket]
    this._goals = new Map(); // action name -> Map(goal hex -> {status, stamp, feedback})
    this._renderQueued = false;
  }

  updateGraph(graph) {
    const actions = actionsIn(graph);
    if (actions.map((a) => a.name).join() === this.actions.map((a) => a.name).join()) return;
    this.actions = actions;
    if (this.visible) this._follow();
    this._queueRender();
  }

  setVisible(visible) {
    if (visible === this.visible) return;
    this.visible = visible;
    if (visible) this._follow();
    else this._stopAll();
    this._queueRender();
  }

  /** What the table shows: [{action, type, goal, status, feedback}]. */
  snapshot() {
    const rows = [];
    for (const action of this.actions) {
      for (const [goal, entry] of this._goals.get(action.name) || []) {
        rows.push({ action: action.name, type: action.type, goal, status: STATUS_NAMES[entry.status] || String(entry.status), feedback: entry.feedback });
      }
    }
    return rows;
  }

  _follow() {
    const wanted = new Set(this.actions.map((a) => a.name));
    for (const name of [...this._sockets.keys()]) {
      if (!wanted.has(name)) this._stop(name);
    }
    for (const name of wanted) {
      if (this._sockets.has(name)) continue;
      this._goals.set(name, new Map());
      const status = new TopicSocket(`${name}${ACTION_INFIX}status`, { mode: "subscribe", onMessage: (msg) => this._status(name, msg) });
      const feedback = new TopicSocket(`${name}${ACTION_INFIX}feedback`, {
        mode: "subscribe",
        rate: FEEDBACK_RATE_HZ,
        onMessage: (msg) => this._feedback(name, msg),
      });
      this._sockets.set(name, [status.open(), feedback.open()]);
    }
  }

  _stop(name) {
    for (const socket of this._sockets.get(name) || []) socket.close();
    this._sockets.delete(name);
    this._goals.delete(name);
  }

  _stopAll() {
    for (const name of [...this._sockets.keys()]) this._stop(name);
  }

  _status(name, msg) {
    const goals = this._goals.get(name);
    if (!goals) return;
    const listed = new Set();
    for (const line of msg.status_list || []) {
      const id = goalIdHex(line.goal_info.goal_id.uuid);
      listed.add(id);
      const stamp = line.goal_info.stamp.sec + line.goal_info.stamp.nanosec * 1e-9;
      goals.set(id, { feedback: "", ...goals.get(id), status: line.status, stamp });
    }
    for (const id of [...goals.keys()]) {
      if (!listed.has(id)) goals.delete(id); // the server forgot it (its result expired)
    }
    this._queueRender();
  }

  _feedback(name, msg) {
    const goal = this._goals.get(name)?.get(goalIdHex(msg.goal_id.uuid));
    if (!goal) return; // not in the status list (yet): it comes with the next status
    const text = JSON.stringify(msg.feedback);
    goal.feedback = text.length > FEEDBACK_CHARS ? `${text.slice(0, FEEDBACK_CHARS)}…` : text;
    this._queueRender();
  }

  _queueRender() {
    if (this._renderQueued) return;
    this._renderQueued = true;
    requestAnimationFrame(() => {
      this._renderQueued = false;
      this._render();
    });
  }

  _render() {
    const rows = [];
    for (const action of this.actions) {
      const goals = [...(this._goals.get(action.name) || [])].sort((a, b) => a[1].stamp - b[1].stamp);
      if (!goals.length) rows.push(this._row(action, null, null));
      for (const [id, goal] of goals) rows.push(this._row(action, id, goal));
    }
    this.body.replaceChildren(...rows);
    this.empty.hidden = this.actions.length > 0;
  }

  _row(action, id, goal) {
    const tr = document.createElement("tr");
    const cell = (text, className = "") => {
      const td = document.createElement("td");
      td.textContent = text;
      if (className) td.className = className;
      tr.append(td);
      return td;
    };
    cell(action.name).title = action.type;
    if (!goal) {
      cell("no goals", "dim");
      cell("");
      cell("");
      return tr;
    }
    tr.dataset.goal = id;
    cell(id.slice(0, 8), "mono").title = id;
    const status = cell(STATUS_NAMES[goal.status] || String(goal.status));
    status.dataset.status = ACTIVE.has(goal.status) ? "running" : "ended";
    cell(goal.feedback, "mono");
    return tr;
  }
}
