// The Parameters tab (rqt_reconfigure, `ros2 param`): pick a node, see its parameters with their
// types and values, edit one; the node's answer is shown as is, its refusal reason included.
// Everything goes through the node's parameter services (/NODE/list_parameters, ...) on the core;
// while the tab is shown, /parameter_events keeps the values current.

import { TopicSocket, callService } from "./api.js";

// rcl_interfaces/msg/ParameterType, and the ParameterValue field holding each type.
const TYPES = {
  1: ["boolean", "bool_value"],
  2: ["integer", "integer_value"],
  3: ["double", "double_value"],
  4: ["string", "string_value"],
  5: ["byte array", "byte_array_value"],
  6: ["boolean array", "bool_array_value"],
  7: ["integer array", "integer_array_value"],
  8: ["double array", "double_array_value"],
  9: ["string array", "string_array_value"],
};
const STRING = 4;
const BYTE_ARRAY = 5;

/** What a ParameterValue holds, as JS (undefined when not set). */
export function valueOf(parameterValue) {
  const entry = TYPES[parameterValue.type];
  return entry ? parameterValue[entry[1]] : undefined;
}

/** The text typed for a parameter as a ParameterValue: read as JSON (`0.5`, `true`, `[1, 2]`),
 * else a string; a string parameter takes the text as typed. The node judges the type. */
export function parameterValueFrom(text, declaredType) {
  let value = text;
  if (declaredType !== STRING) {
    try {
      value = JSON.parse(text);
    } catch {
      value = text;
    }
  }
  const type = typeOf(value);
  if (!type) return null;
  return { type, [TYPES[type][1]]: value };
}

function typeOf(value) {
  if (typeof value === "boolean") return 1;
  if (typeof value === "number") return Number.isInteger(value) ? 2 : 3;
  if (typeof value === "string") return STRING;
  if (!Array.isArray(value)) return 0;
  const kinds = new Set(value.map((item) => (typeof item === "number" ? (Number.isInteger(item) ? 2 : 3) : typeOf(item))));
  if (kinds.size === 2 && kinds.has(2) && kinds.has(3)) return 8;
  if (kinds.size > 1 || kinds.has(0) || kinds.has(undefined)) return 0;
  const [kind = 2] = kinds;
  return kind + 5; // BOOL 1 -> BOOL_ARRAY 6, INTEGER 2 -> 7, DOUBLE 3 -> 8, STRING 4 -> 9
}

function display(value, type) {
  if (value === undefined) return "";
  if (type === STRING) return value;
  const double = (x) => (Number.isInteger(x) ? x.toFixed(1) : String(x)); // 1.0 stays a double
  if (type === 3) return double(value);
  if (type === 8) return `[${value.map(double).join(", ")}]`;
  return JSON.stringify(value);
}

export class ParametersPanel {
  constructor({ node, table, result, refresh }) {
    this.select = node;
    this.body = table.tBodies[0];
    this.resultBox = result;
    this.node = "";
    this.rows = []; // {name, type, value, description, readOnly}
    this.last = null; // the last set: {node, name, kind, message}
    this.visible = false;
    this.events = null;
    this._nodesKey = "";
    node.addEventListener("change", () => this.show(node.value));
    refresh.addEventListener("click", () => this.load());
  }

  /** Offer the nodes that serve parameters (the graph names their services). */
  updateGraph(graph) {
    const services = new Set(graph.services.map((s) => s.name));
    const nodes = graph.nodes.map((n) => n.name).filter((name) => services.has(`${name}/list_parameters`)).sort();
    const key = nodes.join();
    if (key === this._nodesKey) return;
    this._nodesKey = key;
    this.select.replaceChildren(new Option("pick a node", ""), ...nodes.map((name) => new Option(name, name)));
    this.select.value = nodes.includes(this.node) ? this.node : "";
  }

  /** The tab is shown or hidden: follow /parameter_events only while shown. */
  setVisible(visible) {
    this.visible = visible;
    if (visible && !this.events) {
      this.events = new TopicSocket("/parameter_events", {
        queue: 50,
        onMessage: (event) => {
          if (event.node === this.node) this.load();
        },
      }).openWhenPublished();
      if (this.node) this.load();
    } else if (!visible && this.events) {
      this.events.close();
      this.events = null;
    }
  }

  show(node) {
    this.node = node;
    this.select.value = node;
    this.rows = [];
    this._result("none", "");
    this.load();
  }

  async load() {
    const node = this.node;
    if (!node) {
      this._render();
      return;
    }
    const listed = await callService(`${node}/list_parameters`, {});
    if (listed.kind === "error") return this._result("error", `${node}: ${listed.message}`);
    const names = listed.body.result.names;
    const [described, values] = await Promise.all([
      callService(`${node}/describe_parameters`, { names }),
      callService(`${node}/get_parameters`, { names }),
    ]);
    if (described.kind === "error" || values.kind === "error") {
      return this._result("error", `${node}: ${(described.kind === "error" ? described : values).message}`);
    }
    if (node !== this.node) return; // another node was picked meanwhile
    this.rows = names.map((name, i) => {
      const descriptor = described.body.descriptors[i];
      const value = values.body.values[i];
      return {
        name,
        type: value.type || descriptor.type,
        value: valueOf(value),
        description: descriptor.description,
        readOnly: descriptor.read_only,
      };
    });
    this._render();
  }

  async set(name, text) {
    const row = this.rows.find((r) => r.name === name);
    const node = this.node;
    const value = parameterValueFrom(text, row ? row.type : 0);
    if (!value) return this._result("error", `${name}: ${text} is not a parameter value`);
    this._result("pending", `setting ${name} on ${node}…`);
    const answer = await callService(`${node}/set_parameters`, { parameters: [{ name, value }] });
    if (answer.kind === "error") {
      this._result("error", `${name}: ${answer.message}`, name);
    } else {
      const [result] = answer.body.results;
      if (result.successful) this._result("success", `${name} = ${display(valueOf(value), value.type)}`, name);
      else this._result("refused", `${name} refused: ${result.reason}`, name);
    }
    await this.load();
    return this.last;
  }

  _result(kind, message, name = "") {
    this.last = kind === "none" ? null : { node: this.node, name, kind, message };
    this.resultBox.dataset.kind = kind;
    this.resultBox.textContent = kind === "none" ? "" : `${{ success: "✓", refused: "✗", error: "⚠", pending: "…" }[kind]} ${message}`;
  }

  _render() {
    const editing = this.body.contains(document.activeElement) ? document.activeElement.dataset.param : null;
    const rows = this.rows.map((row) => {
      const tr = document.createElement("tr");
      tr.dataset.param = row.name;
      const name = document.createElement("td");
      name.className = "mono";
      name.textContent = row.name;
      name.title = row.description || "";
      const type = document.createElement("td");
      type.className = "dim";
      type.textContent = (TYPES[row.type] || ["not set"])[0] + (row.readOnly ? ", read-only" : "");
      const cell = document.createElement("td");
      const input = document.createElement("input");
      input.dataset.param = row.name;
      input.className = "mono";
      input.value = display(row.value, row.type);
      input.spellcheck = false;
      input.title = row.readOnly ? "read-only: the node will refuse a change" : "Enter to set";
      input.disabled = row.type === BYTE_ARRAY;
      input.addEventListener("keydown", (event) => {
        if (event.key !== "Enter") return;
        input.blur(); // the answer re-renders the row with the node's value
        this.set(row.name, input.value);
      });
      cell.append(input);
      tr.append(name, type, cell);
      return tr;
    });
    if (!rows.length) {
      const tr = document.createElement("tr");
      const td = document.createElement("td");
      td.colSpan = 3;
      td.className = "dim";
      td.textContent = this.node ? "no parameters" : "pick a node to see its parameters";
      tr.append(td);
      rows.push(tr);
    }
    if (editing && this.rows.some((r) => r.name === editing)) return this._updateValues(editing);
    this.body.replaceChildren(...rows);
  }

  /** Values refreshed while the user types in one: leave that input alone. */
  _updateValues(editing) {
    for (const row of this.rows) {
      const input = this.body.querySelector(`input[data-param="${CSS.escape(row.name)}"]`);
      if (input && row.name !== editing) input.value = display(row.value, row.type);
    }
  }
}
