// A message form generated from a type's default instance: one input per scalar field
// (nested names like `point.x`), kept in step with a JSON textarea that holds the whole message
// (arrays and anything else the fields cannot show are edited there).

export class MessageForm {
  constructor({ fields, json, onChange }) {
    this.fieldsBox = fields;
    this.json = json;
    this.onChange = onChange || (() => {});
    this.value = {};
    json.addEventListener("input", () => {
      try {
        this.value = JSON.parse(json.value);
        json.classList.remove("invalid");
        this._renderFields();
      } catch {
        json.classList.add("invalid");
      }
    });
  }

  /** Show `value` (a default instance) in the fields and the textarea. */
  set(value) {
    this.value = structuredClone(value ?? {});
    this.json.value = JSON.stringify(this.value, null, 2);
    this.json.classList.remove("invalid");
    this._renderFields();
  }

  /** The message to send, from the textarea; throws SyntaxError naming the problem. */
  read() {
    return JSON.parse(this.json.value);
  }

  _renderFields() {
    const leaves = [];
    let hasArrays = false;
    const walk = (node, path) => {
      for (const [key, child] of Object.entries(node)) {
        const here = [...path, key];
        if (Array.isArray(child)) hasArrays = true;
        else if (child !== null && typeof child === "object") walk(child, here);
        else leaves.push({ path: here, value: child });
      }
    };
    if (this.value && typeof this.value === "object" && !Array.isArray(this.value)) walk(this.value, []);
    const rows = leaves.map(({ path, value }) => this._field(path, value));
    if (hasArrays) {
      const note = document.createElement("p");
      note.className = "dim small-text";
      note.textContent = "Lists (e.g. poses, points) are edited in the JSON below.";
      rows.push(note);
    }
    if (!leaves.length && !hasArrays) {
      const note = document.createElement("p");
      note.className = "dim small-text";
      note.textContent = "No fields: the message is empty.";
      rows.push(note);
    }
    this.fieldsBox.replaceChildren(...rows);
  }

  _field(path, value) {
    const label = document.createElement("label");
    label.className = "field";
    const name = document.createElement("span");
    name.className = "mono";
    name.textContent = path.join(".");
    const input = document.createElement("input");
    input.dataset.field = path.join(".");
    if (typeof value === "boolean") {
      input.type = "checkbox";
      input.checked = value;
    } else if (typeof value === "number") {
      input.type = "number";
      input.step = "any";
      input.value = String(value);
    } else {
      input.type = "text";
      input.value = value ?? "";
    }
    input.addEventListener("input", () => {
      let next;
      if (input.type === "checkbox") next = input.checked;
      else if (input.type === "number") next = input.value === "" ? 0 : Number(input.value);
      else next = input.value;
      setPath(this.value, path, next);
      this.json.value = JSON.stringify(this.value, null, 2);
      this.json.classList.remove("invalid");
      this.onChange(this.value);
    });
    label.append(name, input);
    return label;
  }
}

function setPath(target, path, value) {
  let node = target;
  for (const key of path.slice(0, -1)) node = node[key];
  node[path[path.length - 1]] = value;
}
